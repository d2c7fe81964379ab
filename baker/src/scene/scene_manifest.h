// manifest.json (docs/formats.md "Manifest"): what the runtime loads (ibl::loadProbeSetFromManifest).
#pragma once

#include "iblbake/scene/scene.h"
#include "iblbake/scene/scene_plan.h"

#include <nlohmann/json.hpp>

#include <filesystem>
#include <map>
#include <string>

namespace ibl {

struct ManifestInputs {
    const Scene& scene;
    const Plan& plan;
    std::map<std::string, std::filesystem::path> entries; // stage id -> cache entry
    std::map<std::string, std::string> keys;              // stage id -> cache key
    std::map<std::string, std::string> productHashes;     // product file name -> content hash
    std::string backend;
};

nlohmann::json buildManifest(const ManifestInputs& inputs);

inline constexpr int kManifestSchemaVersion = 1;

} // namespace ibl
