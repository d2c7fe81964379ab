// A bake's files as the glTF export (gltf_ibl.h) of `iblbake gltf` and of a scene's outputs.gltf: the
// specular chain with the sun taken out of level 0 again where the bake kept it there, re-filtered to the
// roughness stock Babylon.js reads at each level (the babylon engine profile, cube_profile.h), the SH and the
// sun light.
#pragma once

#include "iblbake/baker/gltf_ibl.h"
#include "iblbake/baker/sh.h"
#include "iblbake/baker/specular.h"
#include "iblbake/core/gltf_names.h"
#include "iblbake/opencl/executor.h"

#include <filesystem>
#include <functional>
#include <optional>
#include <string>

namespace ibl {

struct GltfExportSource {
    std::filesystem::path specular;           // specular.ktx2
    std::filesystem::path diffuse;            // diffuse.json
    std::optional<std::filesystem::path> sun; // sun.json, when the bake extracted the sun
};

struct GltfExportSettings {
    int minFaceSize = 16;               // face size of the re-filtered chain's last (roughness-1) level
    std::string quality = "production"; // sample preset of a re-filtered chain (specular.h parseQuality)
};

struct GltfExport {
    GltfIblScene scene;
    // The re-filter of the chain from level 0 (always set: no --mip-mapping bakes the babylon profile's
    // levels); its levelRoughness holds the profile's roughness per level.
    std::optional<SpecularSettings> refilter;
    int baseFaceSize = 0, lowestFaceSize = 0; // of the re-filtered chain
};

// Reads the bake's files. Throws ibl::Error naming the file; SettingError("minFaceSize") when the lowest
// face size min(minFaceSize, level-0 size / 2) is not a power of two.
GltfExport readBakeForGltf(const GltfExportSource& source, const GltfExportSettings& settings);

// Re-filters export.scene.specular when export.refilter is set (else nothing to do).
void refilterForGltf(GltfExport& gltfExport, const Executor& executor);

// The whole export, of `iblbake gltf` and of the scene's gltf-export stage: readBakeForGltf,
// refilterForGltf on executor() (asked for only when the chain must be re-filtered), writeGltfIbl to
// `output` and its images beside it. refilterMilliseconds: the re-filter's wall time (0 without one).
struct GltfExported {
    GltfExport gltf;
    double refilterMilliseconds = 0.0;
};
GltfExported exportGltf(const GltfExportSource& source, const GltfExportSettings& settings,
                        const std::filesystem::path& output,
                        const std::function<const Executor&()>& executor);

// `iblbake gltf`'s report of an export to `output`: the re-filter (on `executorDescription`) when there was
// one, and the file written.
std::string gltfExportText(const GltfExported& exported, const std::filesystem::path& output,
                           const std::string& executorDescription);

// A bake directory's files: specular.ktx2, diffuse.json, and sun.json when it is there.
GltfExportSource gltfExportSourceIn(const std::filesystem::path& bakeDirectory);

// diffuse.json's sh.irradiance (A_l k_i L_i): 9 finite RGB triples; throws ibl::Error naming the file and
// the key path.
ShRgb readPrescaledIrradiance(const std::filesystem::path& diffuseJson);

} // namespace ibl
