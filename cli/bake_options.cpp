#include "bake_options.h"

#include "backend_choice.h"

#include <iostream>

namespace ibl::cli {

BakeOptions BakeRunOptions::bakeOptions() const {
    BakeOptions options;
    options.cacheDirectory = cache;
    options.force = force;
    options.backend = parseBackend(backend);
    options.device = device;
    options.warnings = &std::cerr;
    return options;
}

CLI::App* addBakeSubcommand(CLI::App& app, BakeCommandOptions& o) {
    CLI::App* cmd = app.add_subcommand("bake", "bake what a scene needs (cached stages are not recomputed)");
    cmd->add_option("scene", o.scene, "scene file (JSON, README \"Scenes\")")->required();
    cmd->add_flag("--json", o.json, "JSON event lines on stdout (stage-start, stage-end, done)");
    cmd->add_flag("--quiet", o.quiet, "no progress output");
    cmd->add_flag("--force", o.force, "recompute every stage");
    cmd->add_option("--cache", o.cache, "cache directory (default: <outputs.directory>/.iblbake-cache)");
    addBackendAndDevice(*cmd, o.backend, o.device);
    return cmd;
}

} // namespace ibl::cli
