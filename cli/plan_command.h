// `iblbake plan SCENE [--json]`: the stages a scene needs, and why. Pure (scene file in, text out), so the
// front end (front_end.cpp) answers it without loading the engine; the engine has the same command.
#pragma once

#include <CLI/CLI.hpp>

#include <string>

namespace ibl::cli {

struct PlanOptions {
    std::string scene;
    bool json = false;
};

// Adds the `plan` subcommand, bound to `options` (which must outlive `app`'s parse).
CLI::App* addPlanSubcommand(CLI::App& app, PlanOptions& options);

// Prints the plan on stdout and returns 0; throws ibl::Error for a bad scene before printing anything.
int runPlan(const PlanOptions& options);

} // namespace ibl::cli
