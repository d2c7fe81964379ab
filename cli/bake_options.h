// The command line of `iblbake bake SCENE`, declared once: the engine's bake command and the front end
// (front_end.cpp), which answers an up-to-date bake itself, parse it the same way.
#pragma once

#include <iblbake/bake_scene.h>

#include <CLI/CLI.hpp>

#include <string>

namespace ibl::cli {

struct BakeCommandOptions {
    std::string scene;
    bool json = false;
    bool quiet = false;
    bool force = false;
    std::string cache;
    std::string backend = "auto";
    std::string device;

    BakeOptions bakeOptions() const; // warnings to stderr
};

// Adds the `bake` subcommand, bound to `options` (which must outlive `app`'s parse).
CLI::App* addBakeSubcommand(CLI::App& app, BakeCommandOptions& options);

} // namespace ibl::cli
