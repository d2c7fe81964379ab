// A bake's files as Filament's (iblbake/baker/filament_export.h).
#include "iblbake/baker/filament_export.h"

#include "iblbake/baker/filament_sh.h"
#include "iblbake/baker/gltf_export.h"
#include "iblbake/core/error.h"
#include "iblbake/core/format_text.h"
#include "iblbake/core/gltf_names.h"
#include "iblbake/ktx2/atomic_file.h"
#include "iblbake/ktx2/cube_profile.h"
#include "iblbake/ktx2/ktx1.h"
#include "iblbake/ktx2/output_set.h"

#include <chrono>
#include <cmath>

namespace ibl {

namespace {

namespace fs = std::filesystem;

// The chain's texels as Filament's files hold them: the bake's stored texels / (storageScale x intensity).
Ktx1Cube ktx1Levels(const CubeMapChain& chain, double divisor) {
    Ktx1Cube cube;
    for (const CubeMap& level : chain.levels) {
        std::vector<ImageRGBA> faces(level.faces.begin(), level.faces.end());
        for (ImageRGBA& face : faces)
            for (glm::vec4& texel : face.pixels)
                texel = glm::vec4(glm::vec3(texel) / float(divisor), texel.a);
        cube.levels.push_back(std::move(faces));
    }
    return cube;
}

// The bytes of one KTX1 file; a texel out of range names the file and the profile's storage.
std::string encodeNamed(const Ktx1Cube& cube, const fs::path& file) {
    try {
        return encodeKtx1R11G11B10fCube(cube);
    } catch (const SettingError& e) {
        throw Error(file.string() + ": the filament profile stores R11G11B10F: " + e.what());
    }
}

// Refuses an intensity that leaves level 0's brightest channel (stored / storageScale) beyond R11G11B10F's
// range, naming the smallest power of two that fits (the re-filtered levels are weighted means of level 0's
// texels, so they fit too).
void checkIntensity(const CubeMap& level0, double storageScale, double intensity) {
    if (!(intensity > 0.0) || !std::isfinite(intensity))
        throw SettingError("intensity", std::to_string(intensity) + " is not a positive number");
    double worst = 0.0; // the largest channel / its largest value
    double brightest = 0.0;
    for (const ImageRGBA& face : level0.faces)
        for (const glm::vec4& texel : face.pixels)
            for (int c = 0; c < 3; ++c) {
                const double radiance = double(texel[c]) / storageScale;
                if (std::isfinite(radiance) && radiance / kR11G11B10fLargest[c] > worst) {
                    worst = radiance / kR11G11B10fLargest[c];
                    brightest = radiance;
                }
            }
    if (worst <= intensity) return;
    throw SettingError("intensity",
                       formatText("%g leaves level 0's brightest channel at %g (%g / %g), beyond the "
                                  "filament profile's R11G11B10F (65,024; 64,512 in blue); give "
                                  "at least %g",
                                  intensity, brightest / intensity, brightest, intensity,
                                  std::exp2(std::ceil(std::log2(worst)))));
}

// cmgen names the files after the deploy directory's last component.
std::string deployName(const fs::path& outputDirectory) {
    const fs::path normal = outputDirectory.lexically_normal();
    const std::string name = (normal.has_filename() ? normal : normal.parent_path()).filename().string();
    if (name.empty() || name == "." || name == "..")
        throw Error(outputDirectory.string() + ": the files are named after the directory; give it a name");
    return name;
}

} // namespace

FilamentExported exportFilament(const fs::path& bakeDirectory, const FilamentExportSettings& settings,
                                const fs::path& outputDirectory,
                                const std::function<const Executor&()>& executor) {
    const EngineProfile& profile = engineProfile("filament");
    if (settings.minFaceSize < profile.smallestFace)
        throw SettingError("minFaceSize", std::to_string(settings.minFaceSize) +
                                              " is below the filament profile's smallest face, " +
                                              std::to_string(profile.smallestFace) + " px");
    if ((settings.minFaceSize & (settings.minFaceSize - 1)) != 0)
        throw SettingError("minFaceSize", std::to_string(settings.minFaceSize) + " is not a power of two");
    const std::string name = deployName(outputDirectory);
    FilamentExported exported;
    exported.ibl = outputDirectory / (name + "_ibl.ktx");
    exported.skybox = outputDirectory / (name + "_skybox.ktx");
    exported.shText = outputDirectory / "sh.txt";

    // The bake as the glTF export reads it: level 0 without the extracted sun, the SH, the storage scale.
    const GltfExportSource source = gltfExportSourceIn(bakeDirectory);
    const GltfExport bake = readBakeForGltf(source, {settings.minFaceSize, settings.quality});
    const CubeMap& level0 = bake.scene.specular.levels.front();
    const int base = level0.faceSize;
    if (base < 2 * settings.minFaceSize)
        throw Error(source.specular.string() + ": level 0 is " + std::to_string(base) +
                    " px; the filament profile needs two levels down to " +
                    std::to_string(settings.minFaceSize) + " px, so at least " +
                    std::to_string(2 * settings.minFaceSize));

    // The skybox first: its range checks refuse a bake before the re-filter's work.
    checkIntensity(level0, bake.scene.storageScale, settings.intensity);
    const double divisor = bake.scene.storageScale * settings.intensity;
    CubeMapChain skyboxChain;
    skyboxChain.levels.push_back(level0);
    const std::string skyboxBytes = encodeNamed(ktx1Levels(skyboxChain, divisor), exported.skybox);

    SpecularSettings refilter;
    refilter.quality = parseQuality(settings.quality);
    refilter.levels = gltfRefilteredLevels(base, settings.minFaceSize); // as the glTF export's chain
    refilter.levelRoughness = engineChainRoughness(profile, refilter.levels, base);
    const auto start = std::chrono::steady_clock::now();
    const CubeMapChain chain = bakeSpecular(level0, refilter, executor());
    exported.refilterMilliseconds =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();

    ShRgb irradiance = bake.scene.prescaledIrradiance; // in radiance units: not scaled by storageScale
    for (glm::dvec3& coefficient : irradiance)
        coefficient /= settings.intensity;
    Ktx1Cube ibl = ktx1Levels(chain, divisor);
    ibl.keyValues["sh"] = filamentShMetadata(irradiance);
    const std::string iblBytes = encodeNamed(ibl, exported.ibl);
    const std::string shText = filamentShText(irradiance);

    OutputSet outputs;
    outputs.createDirectories(outputDirectory, "the Filament export");
    outputs.writeFile(exported.ibl, [&](const fs::path& file) { writeFileBytes(file, iblBytes); });
    outputs.writeFile(exported.skybox, [&](const fs::path& file) { writeFileBytes(file, skyboxBytes); });
    outputs.writeFile(exported.shText, [&](const fs::path& file) { writeFileBytes(file, shText); });
    outputs.commit();

    exported.baseFaceSize = base;
    exported.lowestFaceSize = chain.levels.back().faceSize;
    exported.levelRoughness = refilter.levelRoughness;
    return exported;
}

fs::path exportFilamentSh(const fs::path& bakeDirectory, const fs::path& output) {
    const fs::path diffuse = bakeDirectory / "diffuse.json";
    const std::string text = filamentShText(readPrescaledIrradiance(diffuse));
    AtomicFile file(output);
    writeFileBytes(file.tempPath(), text, output.string());
    file.commit();
    return diffuse;
}

std::string filamentExportText(const FilamentExported& exported, const std::string& executorDescription,
                               double intensity) {
    return formatText("refilter %zu levels %d..%d px, %s: %.1f ms\n", exported.levelRoughness.size(),
                      exported.baseFaceSize, exported.lowestFaceSize, executorDescription.c_str(),
                      exported.refilterMilliseconds) +
           formatText(
               "wrote   %s (R11G11B10F, Filament's roughness per level), %s, %s: set the IndirectLight's "
               "intensity to %g\n",
               exported.ibl.c_str(), exported.skybox.c_str(), exported.shText.c_str(), intensity);
}

} // namespace ibl
