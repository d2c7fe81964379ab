// iblbake gltf BAKE_DIR -o scene.gltf: a bake directory as glTF 2.0 (EXT_lights_image_based with RGBD PNG
// faces, the sun as a KHR_lights_punctual directional light); conventions in iblbake/baker/gltf_ibl.h.
#include "bake_dir.h"
#include "commands.h"
#include "common_options.h"

#include <iblbake/baker/calibration.h>
#include <iblbake/baker/gltf_ibl.h>
#include <iblbake/baker/specular.h>
#include <iblbake/baker/sun.h>
#include <iblbake/core/error.h>
#include <iblbake/ktx2/ktx2.h>
#include <iblbake/ktx2/storage_scale.h>
#include <iblbake/runtime/runtime.h>

#include <nlohmann/json.hpp>

#include <bit>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>

namespace fs = std::filesystem;

namespace ibl::cli {
namespace {

struct GltfOptions {
    std::string bakeDir;
    std::string output;
    int minFaceSize = 16;
    std::string quality = "production";
    BackendOptions backend;
};

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
                       double storageScale, const std::filesystem::path& ktxPath) {
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
    if (glm::dot(light.direction, sun->direction) < std::cos(0.1 * 3.14159265358979 / 180.0) ||
        std::abs(light.illuminance / storageScale / sun->illuminance - 1.0) > 0.01)
        throw Error(ktxPath.string() + ": the sun in level 0 is not the one in sun.json");
    return level0;
}

} // namespace

Action addGltfCommand(CLI::App& app) {
    auto o = std::make_shared<GltfOptions>();
    CLI::App* cmd = app.add_subcommand(
        "gltf",
        "export a bake as glTF 2.0: EXT_lights_image_based (RGBD PNG) and the sun as KHR_lights_punctual");
    cmd->add_option("bake", o->bakeDir, "bake directory: specular.ktx2, diffuse.json [, sun.json]")
        ->required();
    cmd->add_option("-o,--output", o->output, "output .gltf; its images are written beside it")->required();
    cmd->add_option("--min-face-size", o->minFaceSize,
                    "face size of the roughness-1 level when the chain is re-filtered (the extension "
                    "suggests 16)")
        ->capture_default_str()
        ->check(CLI::Range(1, 4096));
    cmd->add_option("--quality", o->quality,
                    "sample preset of the re-filtered chain: draft, production, reference")
        ->capture_default_str()
        ->check(CLI::IsMember({"draft", "production", "reference"}));
    o->backend.addTo(*cmd);

    return [o] {
        auto start = std::chrono::steady_clock::now();
        const fs::path dir(o->bakeDir), output(o->output);
        if (output.extension() != ".gltf") throw Error(o->output + ": the glTF is written as .gltf (JSON)");
        const fs::path ktxPath = dir / "specular.ktx2";
        const Ktx2Image ktx = readKtx2(ktxPath);
        CubeMapChain chain = chainFromKtx2(ktxPath, ktx);

        GltfIblScene scene;
        try {
            scene.storageScale = ktx2StorageScale(ktx); // the chain stays as stored; the intensity divides
        } catch (const Error& e) {
            throw Error(ktxPath.string() + ": " + e.what());
        }
        scene.prescaledIrradiance = readPrescaledIrradiance(dir / "diffuse.json");
        if (fs::exists(dir / "sun.json")) {
            const std::string text = readText(dir / "sun.json");
            try {
                scene.sun = diskLightFromJson(text);
                scene.sunInLux = nlohmann::json::parse(text).value("units", "lux") == "lux";
            } catch (const std::exception& e) {
                throw Error((dir / "sun.json").string() + ": " + e.what());
            }
        }

        // A bake whose level 0 kept the extracted sun (iblbake.sunInLevel0): the glTF carries the sun as a
        // KHR light, so level 0 must be the residual. The same detection on the same pixels gives the bake's
        // residual; the light it finds is checked against sun.json.
        if (auto in0 = ktx.keyValues.find("iblbake.sunInLevel0");
            in0 != ktx.keyValues.end() && in0->second == "true")
            chain.levels.front() =
                residualLevel0(chain.levels.front(), ktx, scene.sun, scene.storageScale, ktxPath);

        // The extension maps its levels evenly to roughness 0..1; a linear bake already does, any other
        // is re-filtered from its level 0 (the unconvolved source) down to --min-face-size.
        const auto mapping = ktx.keyValues.find("iblbake.roughnessMapping");
        bool linear = false;
        try {
            linear = mapping != ktx.keyValues.end() &&
                     parseStoredMipMapping(mapping->second) == MipMapping::Linear;
        } catch (const Error& e) {
            throw Error(ktxPath.string() + ": " + e.what());
        }
        std::string levelsNote = "as baked (linear roughness mapping)";
        if (!linear) {
            const int base = chain.levels.front().faceSize;
            if (base < 2) throw Error(ktxPath.string() + ": a 1-texel cube cannot hold roughness 0 and 1");
            const int lowest = std::min(o->minFaceSize, base / 2);
            if ((lowest & (lowest - 1)) != 0)
                throw Error("--min-face-size: " + std::to_string(o->minFaceSize) + " is not a power of two");
            SpecularSettings settings;
            settings.mapping = MipMapping::Linear;
            settings.levels = std::bit_width(unsigned(base / lowest));
            settings.quality = parseQuality(o->quality);
            Executor executor = o->backend.makeExecutor();
            auto bakeStart = std::chrono::steady_clock::now();
            chain = bakeSpecular(chain.levels.front(), settings, executor);
            levelsNote = "re-filtered from level 0 with perceptual roughness m/(N-1), quality " + o->quality;
            std::printf("refilter %d levels %d..%d px, %s: %.1f ms\n", settings.levels, base, lowest,
                        executor.description().c_str(), millisecondsSince(bakeStart));
        }
        scene.specular = std::move(chain);
        scene.extras["iblbake.specularLevels"] = levelsNote;
        for (const auto& [key, value] : ktx.keyValues)
            if (key.rfind("iblbake.calibration", 0) == 0 || key == "iblbake.units" ||
                key == "iblbake.colorSpace" || key == "iblbake.source" ||
                key == std::string("iblbake.") + kLatLongPixelsKey)
                scene.extras[key] = value;

        writeGltfIbl(output, scene);
        std::printf("wrote   %s: %zu levels of %d px faces as RGBD PNG (intensity %.6g)%s\n",
                    o->output.c_str(), scene.specular.levels.size(), scene.specular.levels.front().faceSize,
                    gltfIblIntensity(scene.specular, scene.storageScale),
                    scene.sun ? ", sun as KHR_lights_punctual" : "");
        std::printf("time    %.1f ms\n", millisecondsSince(start));
        return 0;
    };
}

} // namespace ibl::cli
