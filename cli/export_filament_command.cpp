// iblbake export-filament BAKE_DIR -o DIR: a bake as Filament's files, what cmgen --deploy DIR --format=ktx
// writes (iblbake/baker/filament_export.h).
#include "commands.h"
#include "common_options.h"
#include "setting_flags.h"

#include <iblbake/baker/filament_export.h>
#include <iblbake/core/error.h>

#include <cstdio>
#include <memory>
#include <optional>

namespace ibl::cli {
namespace {

struct ExportFilamentOptions {
    std::string bakeDir;
    std::string output;
    FilamentExportSettings settings;
    BackendOptions backend;
};

} // namespace

Action addExportFilamentCommand(CLI::App& app) {
    auto o = std::make_shared<ExportFilamentOptions>();
    CLI::App* cmd = app.add_subcommand(
        "export-filament",
        "export a bake as Filament's NAME_ibl.ktx, NAME_skybox.ktx and sh.txt (cmgen --deploy)");
    cmd->add_option("bake", o->bakeDir, "bake directory: specular.ktx2, diffuse.json [, sun.json]")
        ->required();
    cmd->add_option("-o,--output", o->output, "output directory; its name NAME names the KTX1 files")
        ->required();
    cmd->add_option("--min-face-size", o->settings.minFaceSize,
                    "face size of the roughness-1 level (the filament profile's smallest: 16)")
        ->capture_default_str();
    cmd->add_option("--intensity", o->settings.intensity,
                    "the IndirectLight intensity you set in Filament: the files hold radiance / intensity")
        ->capture_default_str();
    cmd->add_option("--quality", o->settings.quality,
                    "sample preset of the re-filtered chain: draft, production, reference")
        ->capture_default_str()
        ->check(CLI::IsMember({"draft", "production", "reference"}));
    o->backend.addTo(*cmd);

    return [o] {
        const auto start = std::chrono::steady_clock::now();
        std::optional<Executor> executor;
        FilamentExported exported;
        try {
            exported = exportFilament(o->bakeDir, o->settings, o->output, [&]() -> const Executor& {
                return executor.emplace(o->backend.makeExecutor());
            });
        } catch (const SettingError& e) {
            throw Error(flaggedMessage(e));
        }
        BackendOptions::storeBuiltKernels(*executor);
        std::printf("refilter %zu levels %d..%d px, %s: %.1f ms\n", exported.levelRoughness.size(),
                    exported.baseFaceSize, exported.lowestFaceSize, executor->description().c_str(),
                    exported.refilterMilliseconds);
        std::printf(
            "wrote   %s (R11G11B10F, Filament's roughness per level), %s, %s: set the IndirectLight's "
            "intensity to %g\n",
            exported.ibl.c_str(), exported.skybox.c_str(), exported.shText.c_str(), o->settings.intensity);
        std::printf("time    %.1f ms\n", millisecondsSince(start));
        return 0;
    };
}

} // namespace ibl::cli
