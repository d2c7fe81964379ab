// A plan's budget (docs/scenes.md "Budget"): each stage's estimated peak memory and work, from the scene and
// the input files' headers only (no pixel is decoded), and the limits a bake is refused by before any work.
#pragma once

#include "iblbake/scene/scene.h"
#include "iblbake/scene/scene_plan.h"

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace ibl {

struct StageEstimate {
    std::string id, kind;
    std::uint64_t memoryBytes = 0; // the stage's own peak, above the resident base
    std::uint64_t work = 0;        // texels x samples (0: not estimated, see docs/scenes.md "Budget")
    std::string drivingKey;        // the scene key its size follows: "outputs.faceSize", "probes[3].capture"
    std::string what;              // what drives it: "256-px faces", "2,048 x 1,024 source"
};

struct PlanBudget {
    std::vector<StageEstimate> stages; // in plan order
    std::uint64_t baseBytes = 0;       // resident before any stage: the engine, its libraries, the backend
    std::uint64_t peakBytes = 0;       // base + the largest stage's (stages run one at a time)
    std::uint64_t totalWork = 0;       // all stages'
    std::size_t peakStage = 0;         // index into stages of the largest memory
    std::size_t workStage = 0;         // index into stages of the largest work
};

// The estimate for `plan`. Image sizes come from Radiance, OpenEXR and PNG headers; a file of another format
// (or one whose header cannot be read) counts as a lat-long of 4 x 2 faces of its stage. Never throws for a
// missing or unreadable input (the bake reports those).
PlanBudget estimatePlan(const Scene& scene, const Plan& plan);

struct BudgetLimits {
    std::uint64_t maxMemoryBytes = 0; // 0: defaultMaxMemoryBytes()
    std::uint64_t maxWork = 0;        // 0: no limit
};

// 75% of this machine's physical memory (sysconf _SC_PHYS_PAGES x _SC_PAGE_SIZE): the rest is the system's
// and the node's other jobs'.
std::uint64_t defaultMaxMemoryBytes();

// "<scene>: <key>: the plan needs an estimated 37.2 GiB (probe:hall: 4,096-px faces, 2,000 probes), over
// --max-memory 17.9 GiB", the same for --max-work; nothing when the plan fits.
std::optional<std::string> budgetRefusal(const Scene& scene, const PlanBudget& budget,
                                         const BudgetLimits& limits);

// "4G", "512M", "1.5GiB", "800000000": bytes (K, M, G, T are powers of 1,024; an optional "B" or "iB"
// follows). "2e12", "5G": a work count (K, M, G, T powers of 1,000). Throw ibl::Error "<flag>: ..."
// naming the value and the form expected.
std::uint64_t parseByteSize(const std::string& text, const std::string& flag);
std::uint64_t parseWorkCount(const std::string& text, const std::string& flag);

// "37.2 GiB", "245 MiB", "812 KiB".
std::string bytesText(std::uint64_t bytes);

// `iblbake plan`'s lines: each stage's memory and work, the peak and the total, against the limits.
std::string budgetText(const PlanBudget& budget, const BudgetLimits& limits);
nlohmann::json budgetToJson(const PlanBudget& budget, const BudgetLimits& limits);

} // namespace ibl
