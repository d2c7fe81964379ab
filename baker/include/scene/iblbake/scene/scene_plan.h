// The planner: a pure function from a scene to the stages its products need, each with its inputs,
// settings and the reason it runs, and the stages it leaves out with the reason (docs/scenes.md "Plan").
#pragma once

#include "iblbake/scene/scene.h"

#include <mip_mapping.h>

#include <nlohmann/json.hpp>

#include <filesystem>
#include <string>
#include <vector>

namespace ibl {

// The distant chain's rough layers (docs/formats.md "Rough layers"), beside specular.ktx2 when a material
// reads past r_0.
inline constexpr const char* kRoughLayersFile = "specular_rough.ktx2";

struct PlanInput {
    std::string keyPath; // where the scene names it, e.g. "probes[1].capture"
    std::filesystem::path file;
};

struct PlanStage {
    std::string id;   // "dfg", "environment", "sun", "specular", "diffuse", "probe:<name>"
    std::string kind; // "dfg-lut", "environment", "sun-extract", "specular-ld", "diffuse-sh", "probe-ld"
    std::vector<std::string> dependsOn; // ids of earlier stages whose products it reads
    std::vector<PlanInput> inputs;      // files read
    nlohmann::json settings;            // everything else its products depend on
    std::vector<std::string> products;  // files it adds to the output directory (none: cache only)
    bool usesBackend = false;           // runs kernels (OpenCL or CPU: the cache key names which)
    std::string reason;
};

struct SkippedStage {
    std::string id, kind, reason;
};

struct Plan {
    std::vector<PlanStage> stages; // in an order where every stage follows its dependencies
    std::vector<SkippedStage> skipped;
    std::vector<std::string> notes; // what the manifest records about unused parts of products
};

Plan planScene(const Scene& scene);

// {"stages": [{id, kind, dependsOn, inputs: [{key, file}], settings, products, reason}], "skipped": [...],
//  "notes": [...]}
nlohmann::json planToJson(const Plan& plan);
// The plan for people (`iblbake plan`): the scene, each stage with its reason, settings, inputs, dependencies
// and products, the skipped stages, the notes; one line each.
std::string planText(const Scene& scene, const Plan& plan);

// The last level the roughest material reads in a chain of `levels` levels: the first level m whose
// roughness under `mapping` (mip_mapping.h) reaches roughnessMax. Levels past it are not integrated
// (specular.h SpecularSettings::integratedLevels).
int lastLevelNeeded(int levels, MipMapping mapping, double roughnessMax);

} // namespace ibl
