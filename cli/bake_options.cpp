#include "bake_options.h"

#include "backend_choice.h"

#include <iostream>

namespace ibl::cli {

BakeOptions BakeRunOptions::bakeOptions() const {
    return {.cacheDirectory = cache,
            .force = force,
            .backend = parseBackend(backend),
            .device = device,
            .warnings = &std::cerr,
            .outputRoot = outputRoot,
            .budget = {maxMemory.empty() ? 0 : parseByteSize(maxMemory, "--max-memory"),
                       maxWork.empty() ? 0 : parseWorkCount(maxWork, "--max-work")}};
}

void BakeRunOptions::addTo(CLI::App& command, const char* forceHelp, const char* cacheHelp) {
    command.add_flag("--json", json, "JSON event lines on stdout");
    command.add_flag("--quiet", quiet, "no progress output (failures still go to stderr)");
    command.add_flag("--force", force, forceHelp);
    command.add_option("--cache", cache, cacheHelp);
    command.add_option("--output-root", outputRoot, "write only below this directory (docs/scenes.md)")
        ->envname("IBLBAKE_OUTPUT_ROOT");
    command.add_option("--max-memory", maxMemory,
                       "refuse a bake estimated over this (4G; default 75% of RAM)");
    command.add_option("--max-work", maxWork, "refuse a bake estimated over this many texel-samples (2e12)");
    addBackendAndDevice(command, backend, device);
}

Scene BakeCommandOptions::loadScene() const {
    Scene loaded = loadSceneFile(scene);
    if (clampToFormat) loaded.outputs.clampToFormat = true;
    return loaded;
}

CLI::App* addBakeSubcommand(CLI::App& app, BakeCommandOptions& o) {
    CLI::App* cmd = app.add_subcommand("bake", "bake what a scene needs (cached stages are not recomputed)");
    cmd->add_option("scene", o.scene, "scene file (JSON, docs/scenes.md \"Schema\")")->required();
    o.addTo(*cmd, "recompute every stage", "cache directory (default: <outputs.directory>/.iblbake-cache)");
    cmd->add_flag(
        "--clamp-to-format", o.clampToFormat,
        "clamp the KTX2 products to their format's range (as outputs.clampToFormat: the energy lost "
        "is reported) instead of storing them with a storage scale");
    return cmd;
}

} // namespace ibl::cli
