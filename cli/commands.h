// Subcommand registration: each adds itself to the app and returns the action to run when chosen.
#pragma once

#include <CLI/CLI.hpp>

#include <functional>

namespace ibl::cli {

using Action = std::function<int()>;

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
