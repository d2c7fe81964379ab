// iblbake gltf BAKE_DIR -o scene.gltf: a bake directory as glTF 2.0 (EXT_lights_image_based with RGBD PNG
// faces, the sun as a KHR_lights_punctual directional light); conventions in iblbake/baker/gltf_ibl.h.
#include "commands.h"
#include "common_options.h"
#include "setting_flags.h"

#include <iblbake/baker/gltf_export.h>
#include <iblbake/core/error.h>

#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>

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
        GltfExportSource source{dir / "specular.ktx2", dir / "diffuse.json", std::nullopt};
        if (fs::exists(dir / "sun.json")) source.sun = dir / "sun.json";
        GltfExport gltf;
        try {
            gltf = readBakeForGltf(source, {o->minFaceSize, o->quality});
        } catch (const SettingError& e) {
            throw Error(flaggedMessage(e));
        }
        std::optional<Executor> executor; // only to refilter
        if (gltf.refilter) {
            executor = o->backend.makeExecutor();
            auto bakeStart = std::chrono::steady_clock::now();
            refilterForGltf(gltf, *executor);
            std::printf("refilter %d levels %d..%d px, %s: %.1f ms\n", gltf.refilter->levels,
                        gltf.baseFaceSize, gltf.lowestFaceSize, executor->description().c_str(),
                        millisecondsSince(bakeStart));
        }
        const GltfIblScene& scene = gltf.scene;
        writeGltfIbl(output, scene);
        if (executor) BackendOptions::storeBuiltKernels(*executor);
        std::printf("wrote   %s: %zu levels of %d px faces as RGBD PNG (intensity %.6g)%s\n",
                    o->output.c_str(), scene.specular.levels.size(), scene.specular.levels.front().faceSize,
                    gltfIblIntensity(scene.specular, scene.storageScale),
                    scene.sun ? ", sun as KHR_lights_punctual" : "");
        std::printf("time    %.1f ms\n", millisecondsSince(start));
        return 0;
    };
}

} // namespace ibl::cli
