// iblbake: the command-line front end. It parses, calls the baker library and prints; every failure
// is one line on stderr ("iblbake: error: ...") with a non-zero exit code.
#include "commands.h"
#include "setting_flags.h"

#include <iblbake/bake_state/code_identity.h>
#include <iblbake/baker/process_memory.h>
#include <iblbake/core/error.h>
#include <iblbake/core/one_line.h>

#include <cstdio>
#include <filesystem>
#include <map>
#include <new>
#include <string>

int main(int argc, char** argv) {
    ibl::reuseFreedBlocks();
    CLI::App app{"iblbake: image-based-lighting and light-probe baker", "iblbake"};
    app.require_subcommand(1);
    // The stage-code digest names the code behind cached stages (docs/scenes.md "Cache").
    app.set_version_flag("--version", std::string("iblbake " IBLBAKE_VERSION " (stage code ") +
                                          ibl::builtInCodeDigest() + ")");

    std::map<const CLI::App*, ibl::cli::Action> actions;
    auto add = [&](ibl::cli::Action action) { actions[app.get_subcommands({}).back()] = std::move(action); };
    using namespace ibl::cli;
    for (auto addCommand :
         {addDevicesCommand, addDfgCommand, addSpecularCommand, addDiffuseCommand, addInspectCommand,
          addCalibrateCommand, addPreviewCommand, addPlanCommand, addBakeCommand, addBatchCommand,
          addGltfCommand, addExportShCommand, addExportFilamentCommand, addAccuracyCommand,
          addLightCardCommand, addFormatCostCommand})
        add(addCommand(app));

    try {
        app.parse(argc, argv);
    } catch (const CLI::Success& e) {
        return app.exit(e); // --help, --version
    } catch (const CLI::ParseError& e) {
        std::fprintf(stderr, "iblbake: error: %s (see --help)\n", e.what());
        return 2;
    }
    try {
        for (const auto& [command, action] : actions)
            if (command->parsed()) return action();
        return 2;
    } catch (const ibl::SettingError& e) { // a library error about a setting: the flag that set it in front
        std::fprintf(stderr, "iblbake: error: %s\n", ibl::oneLine(ibl::cli::flaggedMessage(e)).c_str());
        return 1;
    } catch (const ibl::Error& e) {
        std::fprintf(stderr, "iblbake: error: %s\n", ibl::oneLine(e.what()).c_str());
        return 1;
    } catch (const std::filesystem::filesystem_error& e) { // a path the user gave: its name and the reason
        std::fprintf(stderr, "iblbake: error: %s: %s\n",
                     ibl::oneLine(ibl::printableForMessage(e.path1().string())).c_str(),
                     e.code().message().c_str());
        return 1;
    } catch (const std::bad_alloc&) { // the limits (iblbake/core/limits.h) keep inputs from getting here
        std::fprintf(stderr, "iblbake: error: not enough memory\n");
        return 1;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "iblbake: internal error: %s\n", ibl::oneLine(e.what()).c_str());
        return 3;
    }
}
