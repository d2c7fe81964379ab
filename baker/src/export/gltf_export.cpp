// A bake's files as a glTF export (iblbake/baker/gltf_export.h): the flow of `iblbake gltf` and of the
// scene's gltf-export stage.
#include "iblbake/baker/gltf_export.h"

#include "iblbake/baker/calibration.h"
#include "iblbake/baker/products.h"
#include "iblbake/baker/sun.h"
#include "iblbake/core/error.h"
#include "iblbake/core/format_text.h"
#include "iblbake/core/numeric.h"
#include "iblbake/ktx2/cube_profile.h"
#include "iblbake/ktx2/ktx2.h"
#include "iblbake/ktx2/storage_scale.h"
#include "iblbake/runtime/runtime.h"

#include <nlohmann/json.hpp>

#include <chrono>
#include <cmath>

namespace ibl {

namespace {

namespace fs = std::filesystem;

CubeMapChain chainFromKtx2(const fs::path& path, const Ktx2Image& ktx) {
    if (ktx.faceCount != 6 || ktx.pixelWidth != ktx.pixelHeight)
        throw Error(path.string() + ": not a cube map (" + std::to_string(ktx.faceCount) + " faces)");
    CubeMapChain chain;
    for (const std::vector<ImageRGBA>& faces : ktx.levels) {
        CubeMap level;
        level.faceSize = faces.front().width;
        for (int f = 0; f < 6; ++f)
            level.faces[std::size_t(f)] = faces[std::size_t(f)];
        chain.levels.push_back(std::move(level));
    }
    return chain;
}

// The residual the bake took the sun out of, from a level 0 that kept it (iblbake.sunInLevel0): the same
// detection (iblbake.sunMaxSolidAngle) on the same pixels, checked against the bake's sun.json (level 0
// as stored: radiance x storageScale).
CubeMap residualLevel0(CubeMap level0, const Ktx2Image& ktx, const std::optional<DiskLight>& sun,
                       double storageScale, const fs::path& ktxPath) {
    auto value = [&](const char* key) {
        auto it = ktx.keyValues.find(key);
        return it == ktx.keyValues.end() ? std::string() : it->second;
    };
    if (!sun)
        throw Error(ktxPath.string() + ": level 0 holds the extracted sun, but the bake has no sun.json");
    const glm::dvec3 weights = workingLuminanceWeights(value("iblbake.colorSpace"));
    SunDetectSettings settings;
    settings.luminanceWeights = weights;
    try {
        if (std::string limit = value("iblbake.sunMaxSolidAngle"); !limit.empty())
            settings.maxSolidAngle = std::stod(limit);
    } catch (const std::exception&) {
        throw Error(ktxPath.string() + ": iblbake.sunMaxSolidAngle is not a number");
    }
    const SunDetection detection = detectSun(level0, settings);
    if (!detection.found)
        throw Error(ktxPath.string() +
                    ": level 0 holds the extracted sun, but it is not found again: " + detection.reason);
    const DiskLight light = extractSun(level0, detection, weights);
    if (glm::dot(light.direction, sun->direction) < std::cos(0.1 * kDegree) ||
        std::abs(light.illuminance / storageScale / sun->illuminance - 1.0) > 0.01)
        throw Error(ktxPath.string() + ": the sun in level 0 is not the one in sun.json");
    return level0;
}

} // namespace

ShRgb readPrescaledIrradiance(const fs::path& path) {
    try {
        const nlohmann::json doc = nlohmann::json::parse(readText(path));
        const nlohmann::json& c = doc.at("sh").at("irradiance");
        if (!c.is_array() || c.size() != 9) throw Error(path.string() + ": sh.irradiance needs 9 entries");
        ShRgb sh{};
        for (std::size_t i = 0; i < 9; ++i) {
            if (!c[i].is_array() || c[i].size() != 3)
                throw Error(path.string() + ": sh.irradiance[" + std::to_string(i) + "] needs 3 numbers");
            for (std::size_t k = 0; k < 3; ++k) {
                sh[i][int(k)] = c[i][k].get<double>();
                if (!std::isfinite(sh[i][int(k)]))
                    throw Error(path.string() + ": sh.irradiance[" + std::to_string(i) + "] is not finite");
            }
        }
        return sh;
    } catch (const nlohmann::json::exception& e) {
        throw Error(path.string() + ": " + e.what());
    }
}

GltfExport readBakeForGltf(const GltfExportSource& source, const GltfExportSettings& settings) {
    const fs::path& ktxPath = source.specular;
    const Ktx2Image ktx = readKtx2(ktxPath);
    CubeMapChain chain = chainFromKtx2(ktxPath, ktx);

    GltfExport out;
    GltfIblScene& scene = out.scene;
    try {
        scene.storageScale = ktx2StorageScale(ktx); // the chain stays as stored; the intensity divides
    } catch (const Error& e) {
        throw Error(ktxPath.string() + ": " + e.what());
    }
    scene.prescaledIrradiance = readPrescaledIrradiance(source.diffuse);
    if (source.sun) {
        const std::string text = readText(*source.sun);
        try {
            scene.sun = diskLightFromJson(text);
            scene.sunInLux = nlohmann::json::parse(text).value("units", "lux") == "lux";
        } catch (const std::exception& e) {
            throw Error(source.sun->string() + ": " + e.what());
        }
    }

    // A bake whose level 0 kept the extracted sun (iblbake.sunInLevel0): the glTF carries the sun as a
    // KHR light, so level 0 must be the residual. The same detection on the same pixels gives the bake's
    // residual; the light it finds is checked against sun.json.
    if (auto in0 = ktx.keyValues.find("iblbake.sunInLevel0");
        in0 != ktx.keyValues.end() && in0->second == "true")
        chain.levels.front() =
            residualLevel0(chain.levels.front(), ktx, scene.sun, scene.storageScale, ktxPath);

    // The levels hold what stock Babylon.js reads there (the babylon engine profile, cube_profile.h), which
    // no --mip-mapping bakes: the chain is re-filtered from its level 0 (the unconvolved source) down to the
    // lowest face size.
    const EngineProfile& profile = engineProfile(scene.profile);
    const int base = chain.levels.front().faceSize;
    if (base < 2) throw Error(ktxPath.string() + ": a 1-texel cube cannot hold roughness 0 and 1");
    const int lowest = gltfLowestFaceSize(base, settings.minFaceSize);
    if ((lowest & (lowest - 1)) != 0)
        throw SettingError("minFaceSize", std::to_string(settings.minFaceSize) + " is not a power of two");
    SpecularSettings refilter;
    refilter.levels = gltfRefilteredLevels(base, settings.minFaceSize);
    refilter.quality = parseQuality(settings.quality);
    refilter.levelRoughness = engineChainRoughness(profile, refilter.levels, base);
    std::string roughnessList;
    for (const float r : refilter.levelRoughness)
        roughnessList += (roughnessList.empty() ? "" : ", ") + nlohmann::json(r).dump();
    out.refilter = refilter;
    out.baseFaceSize = base;
    out.lowestFaceSize = lowest;
    scene.extras["iblbake.profile"] = profile.name;
    scene.extras["iblbake.levelRoughness"] = roughnessList;
    const std::string levelsNote =
        "re-filtered from level 0 with the perceptual roughness Babylon.js reads at "
        "each level (its getLodFromAlphaG with the loader's lodGenerationScale), "
        "quality " +
        settings.quality;
    scene.specular = std::move(chain);
    scene.extras["iblbake.specularLevels"] = levelsNote;
    for (const auto& [key, value] : ktx.keyValues)
        if (key.rfind("iblbake.calibration", 0) == 0 || key == "iblbake.units" ||
            key == "iblbake.colorSpace" || key == "iblbake.source" ||
            key == std::string("iblbake.") + kLatLongPixelsKey)
            scene.extras[key] = value;
    return out;
}

void refilterForGltf(GltfExport& e, const Executor& executor) {
    if (e.refilter) e.scene.specular = bakeSpecular(e.scene.specular.levels.front(), *e.refilter, executor);
}

GltfExported exportGltf(const GltfExportSource& source, const GltfExportSettings& settings,
                        const fs::path& output, const std::function<const Executor&()>& executor) {
    GltfExported exported{readBakeForGltf(source, settings), 0.0};
    if (exported.gltf.refilter) {
        const Executor& refilterExecutor = executor();
        const auto start = std::chrono::steady_clock::now();
        refilterForGltf(exported.gltf, refilterExecutor);
        exported.refilterMilliseconds =
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    }
    writeGltfIbl(output, exported.gltf.scene);
    return exported;
}

GltfExportSource gltfExportSourceIn(const fs::path& bakeDirectory) {
    GltfExportSource source{bakeDirectory / "specular.ktx2", bakeDirectory / "diffuse.json", std::nullopt};
    if (fs::exists(bakeDirectory / "sun.json")) source.sun = bakeDirectory / "sun.json";
    return source;
}

std::string gltfExportText(const GltfExported& exported, const std::filesystem::path& output,
                           const std::string& executorDescription) {
    const GltfExport& gltf = exported.gltf;
    std::string text;
    if (gltf.refilter)
        text = formatText("refilter %d levels %d..%d px, %s: %.1f ms\n", gltf.refilter->levels,
                          gltf.baseFaceSize, gltf.lowestFaceSize, executorDescription.c_str(),
                          exported.refilterMilliseconds);
    const GltfIblScene& scene = gltf.scene;
    return text + formatText("wrote   %s: %zu levels of %d px faces as RGBD PNG (intensity %.6g)%s\n",
                             output.string().c_str(), scene.specular.levels.size(),
                             scene.specular.levels.front().faceSize, gltfIblIntensity(scene),
                             scene.sun ? ", sun as KHR_lights_punctual" : "");
}

} // namespace ibl
