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
        if (fs::path(o->output).extension() != ".gltf")
            throw Error(o->output + ": the glTF is written as .gltf (JSON)");
        std::optional<Executor> executor; // only to refilter
        GltfExported exported;
        try {
            exported =
                exportGltf(gltfExportSourceIn(o->bakeDir), {o->minFaceSize, o->quality}, o->output,
                           [&]() -> const Executor& { return executor.emplace(o->backend.makeExecutor()); });
        } catch (const SettingError& e) {
            throw Error(flaggedMessage(e));
        }
        if (executor) BackendOptions::storeBuiltKernels(*executor);
        std::printf("%s",
                    gltfExportText(exported, o->output, executor ? executor->description() : "").c_str());
        std::printf("time    %.1f ms\n", millisecondsSince(start));
        return 0;
    };
}

} // namespace ibl::cli
