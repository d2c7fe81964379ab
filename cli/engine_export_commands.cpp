// iblbake gltf BAKE_DIR -o scene.gltf and iblbake export-filament BAKE_DIR -o DIR: a bake directory
// re-filtered for an engine's own roughness per level and written in its files (iblbake/baker/gltf_export.h:
// glTF 2.0, EXT_lights_image_based with RGBD PNG faces, the sun as KHR_lights_punctual; filament_export.h:
// what cmgen --deploy DIR --format=ktx writes). The flows are the library's; this parses and prints.
#include "commands.h"
#include "common_options.h"
#include "setting_flags.h"

#include <iblbake/baker/filament_export.h>
#include <iblbake/baker/gltf_export.h>
#include <iblbake/core/error.h>

#include <cstdio>
#include <filesystem>
#include <optional>

namespace ibl::cli {
namespace {

// What both exports take: the bake, the output, the re-filtered chain's smallest face and sample preset, the
// backend it runs on.
struct EngineExportOptions {
    std::string bakeDir, output;
    int minFaceSize = 16;
    std::string quality = "production";
    double intensity = 1.0; // export-filament
    BackendOptions backend;
    std::optional<Executor> executor; // made only to re-filter

    void addTo(CLI::App& command, const char* outputHelp, const char* minFaceSizeHelp) {
        command.add_option("bake", bakeDir, "bake directory: specular.ktx2, diffuse.json [, sun.json]")
            ->required();
        command.add_option("-o,--output", output, outputHelp)->required();
        command.add_option("--min-face-size", minFaceSize, minFaceSizeHelp)->capture_default_str();
        addQualityOption(command, quality, "the re-filtered chain");
        backend.addTo(command);
    }
    // Runs an export given the executor it asks for, naming the flag of a refused setting; then keeps the
    // kernels it built and prints `text` of its result and the time.
    template <typename Export, typename Text>
    int run(const Export& exportBake, const Text& text) {
        const auto start = std::chrono::steady_clock::now();
        const auto makeExecutor = [&]() -> const Executor& {
            return executor.emplace(backend.makeExecutor());
        };
        try {
            const auto exported = exportBake(makeExecutor);
            if (executor) BackendOptions::storeBuiltKernels(*executor);
            std::printf("%s", text(exported, executor ? executor->description() : "").c_str());
        } catch (const SettingError& e) {
            throw Error(flaggedMessage(e));
        }
        std::printf("time    %.1f ms\n", millisecondsSince(start));
        return 0;
    }
};

} // namespace

Action addGltfCommand(CLI::App& app) {
    auto [o, cmd] = addSubcommand<EngineExportOptions>(
        app, "gltf",
        "export a bake as glTF 2.0: EXT_lights_image_based (RGBD PNG) and the sun as KHR_lights_punctual");
    o->addTo(*cmd, "output .gltf; its images are written beside it",
             "face size of the roughness-1 level when the chain is re-filtered (the extension suggests 16)");
    return [o = o] {
        if (std::filesystem::path(o->output).extension() != ".gltf")
            throw Error(o->output + ": the glTF is written as .gltf (JSON)");
        return o->run(
            [&](const auto& executor) {
                return exportGltf(gltfExportSourceIn(o->bakeDir), {o->minFaceSize, o->quality}, o->output,
                                  executor);
            },
            [&](const GltfExported& e, const std::string& device) {
                return gltfExportText(e, o->output, device);
            });
    };
}

Action addExportFilamentCommand(CLI::App& app) {
    auto [o, cmd] = addSubcommand<EngineExportOptions>(
        app, "export-filament",
        "export a bake as Filament's NAME_ibl.ktx, NAME_skybox.ktx and sh.txt (cmgen --deploy)");
    o->addTo(*cmd, "output directory; its name NAME names the KTX1 files",
             "face size of the roughness-1 level (the filament profile's smallest: 16)");
    cmd->add_option("--intensity", o->intensity,
                    "the IndirectLight intensity you set in Filament: the files hold radiance / intensity")
        ->capture_default_str();
    return [o = o] {
        return o->run(
            [&](const auto& executor) {
                return exportFilament(o->bakeDir, {o->minFaceSize, o->quality, o->intensity}, o->output,
                                      executor);
            },
            [&](const FilamentExported& e, const std::string& device) {
                return filamentExportText(e, device, o->intensity);
            });
    };
}

} // namespace ibl::cli
