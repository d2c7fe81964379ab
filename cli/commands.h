// Subcommand registration: each adds itself to the app and returns the action to run when chosen.
#pragma once

#include <CLI/CLI.hpp>

#include <functional>
#include <memory>
#include <utility>

namespace ibl::cli {

using Action = std::function<int()>;

// A subcommand and the options its flags parse into: CLI11 keeps pointers into the options until the action
// runs, so they live in a shared object that the action holds.
template <class Options>
std::pair<std::shared_ptr<Options>, CLI::App*> addSubcommand(CLI::App& app, const char* name,
                                                             const char* description) {
    return {std::make_shared<Options>(), app.add_subcommand(name, description)};
}

Action addDevicesCommand(CLI::App& app);
Action addDfgCommand(CLI::App& app);
Action addSpecularCommand(CLI::App& app);
Action addDiffuseCommand(CLI::App& app);
Action addInspectCommand(CLI::App& app);
Action addCalibrateCommand(CLI::App& app);
Action addPreviewCommand(CLI::App& app);
Action addPlanCommand(CLI::App& app);
Action addBakeCommand(CLI::App& app);
Action addBatchCommand(CLI::App& app);
Action addGltfCommand(CLI::App& app);
Action addExportShCommand(CLI::App& app);
Action addExportFilamentCommand(CLI::App& app);
Action addAccuracyCommand(CLI::App& app);
Action addLightCardCommand(CLI::App& app);
Action addFormatCostCommand(CLI::App& app);

} // namespace ibl::cli
