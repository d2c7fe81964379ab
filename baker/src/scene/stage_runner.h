// The stage runner (docs/architecture.md "One stage runner"): a plan's stages in order, each stage's entry
// found in the stage cache by its key or made by running the stage into a staging directory of it. Scene
// bakes, batch items and the single-product commands (product_plans.h) all run their plans through it.
#pragma once

#include "iblbake/bake_state/bake_state.h"
#include "iblbake/opencl/executor.h"
#include "iblbake/scene/scene_plan.h"
#include "stage_cache.h"

#include <filesystem>
#include <functional>
#include <map>
#include <string>
#include <vector>

namespace ibl {

struct StageRunner {
    std::string name; // in front of the stages' errors: the scene's name, or the command's
    const StageCache& cache;
    // The backend of the stages that use one, asked for before the first of them runs (so a command's OpenCL
    // set-up overlaps its ingest); may return nullptr when no stage uses it.
    std::function<const Executor*()> executor;
    bool force = false; // run every stage, even those the cache holds
    ProgressSink& progress;
};

struct StageRun {
    std::map<std::string, std::filesystem::path> entries; // stage id -> its entry (found or staged)
    std::vector<StagedEntry> ran; // the staged entries, for the caller to commit once its outputs are written
};

// results[i] belongs to plan.stages[i] and holds its key; each gets its status and seconds, and the progress
// sink its start, waits and end. `current` is the index of the stage running (plan.stages.size() once all
// ran), for the caller's report of a failure. Stage errors propagate (ibl::Error, one line).
StageRun runStages(const StageRunner& runner, const Plan& plan, std::vector<StageResult>& results,
                   std::size_t& current);

} // namespace ibl
