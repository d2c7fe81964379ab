// The command line of `iblbake bake SCENE`, declared once: the engine's bake command and the front end
// (front_end.cpp), which answers an up-to-date bake itself, parse it the same way; `iblbake batch` shares
// BakeRunOptions.
#pragma once

#include <iblbake/bake_state/bake_state.h>
#include <iblbake/scene/scene.h>

#include <CLI/CLI.hpp>

#include <string>

namespace ibl::cli {

// What `iblbake bake` and `iblbake batch` share: how they report, the cache and the backend.
struct BakeRunOptions {
    bool json = false;
    bool quiet = false;
    bool force = false;
    std::string cache;
    std::string backend = "auto";
    std::string device;
    std::string outputRoot;         // --output-root, else $IBLBAKE_OUTPUT_ROOT
    std::string maxMemory, maxWork; // --max-memory, --max-work (parsed by the library: plan_budget.h)

    BakeOptions bakeOptions() const; // warnings to stderr
    // --json, --quiet, --force, --cache, --output-root, --max-memory, --max-work, --backend, --device.
    void addTo(CLI::App& command, const char* forceHelp, const char* cacheHelp);
};

struct BakeCommandOptions : BakeRunOptions {
    std::string scene;
    bool clampToFormat = false; // --clamp-to-format: sets the scene's outputs.clampToFormat

    // The scene file with the command line's settings applied.
    Scene loadScene() const;
};

// Adds the `bake` subcommand, bound to `options` (which must outlive `app`'s parse).
CLI::App* addBakeSubcommand(CLI::App& app, BakeCommandOptions& options);

} // namespace ibl::cli
