// A bake's files as Filament reads them (the filament engine profile, cube_profile.h; docs/engines.md
// "Filament"): what `cmgen --deploy DIR --format=ktx` writes into DIR, named after DIR's last component NAME:
// NAME_ibl.ktx (the specular chain re-filtered from level 0 to the roughness Filament reads at each level,
// down to 16-px faces, with the pre-scaled SH as its key "sh"), NAME_skybox.ktx (level 0) and sh.txt. Both
// KTX1 files are R11G11B10F cube maps (ktx1.h).
#pragma once

#include "iblbake/opencl/executor.h"

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace ibl {

struct FilamentExportSettings {
    int minFaceSize = 16; // face size of the last (roughness-1) level; at least the profile's 16
    std::string quality = "production"; // sample preset of the re-filtered chain (specular.h parseQuality)
    // The IndirectLight intensity the user sets in Filament (IndirectLight::Builder::intensity, default
    // 30,000 there): Filament multiplies the texels and the SH by it (iblLuminance = intensity x exposure),
    // so the files hold radiance / intensity and irradiance / intensity. A bake in cd/m2 needs one that
    // brings its brightest texel within R11G11B10F's range.
    double intensity = 1.0;
};

struct FilamentExported {
    std::filesystem::path ibl, skybox, shText;
    int baseFaceSize = 0, lowestFaceSize = 0;
    std::vector<float> levelRoughness; // the perceptual roughness each level of NAME_ibl.ktx holds
    double refilterMilliseconds = 0.0; // the re-filter's wall time
};

// Reads BAKE_DIR's specular.ktx2, diffuse.json and sun.json (as `iblbake gltf` does: level 0 without the
// extracted sun, texels back in radiance), re-filters on executor() and writes the three files into
// `outputDirectory`, all of them or none. Refusals, before any file is written: SettingError("minFaceSize")
// below the profile's smallest face or not a power of two; SettingError("intensity") when it is not positive
// and finite, or when level 0's brightest channel / intensity is beyond R11G11B10F's range (65,024; 64,512
// for blue), naming the smallest power of two that fits; ibl::Error naming specular.ktx2 when level 0 is too
// small for two levels down to minFaceSize, and naming NAME_*.ktx when a texel is negative or not finite.
FilamentExported exportFilament(const std::filesystem::path& bakeDirectory,
                                const FilamentExportSettings& settings,
                                const std::filesystem::path& outputDirectory,
                                const std::function<const Executor&()>& executor);

// `iblbake export-sh --profile filament`: BAKE_DIR's diffuse.json as cmgen's sh.txt (filament_sh.h), written
// to `output` whole or not at all. Returns the diffuse.json it read.
std::filesystem::path exportFilamentSh(const std::filesystem::path& bakeDirectory,
                                       const std::filesystem::path& output);

// `iblbake export-filament`'s report: the re-filter (on `executorDescription`), the files and the intensity
// to set in Filament.
std::string filamentExportText(const FilamentExported& exported, const std::string& executorDescription,
                               double intensity);

} // namespace ibl
