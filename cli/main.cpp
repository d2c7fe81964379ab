// iblbake: the command-line front end. It parses, calls the baker library and prints; every failure
// is one line on stderr ("iblbake: error: ...") with a non-zero exit code.
#include "commands.h"

#include <iblbake/error.h>

#include <cstdio>
#include <map>

int main(int argc, char** argv) {
    CLI::App app{"iblbake: image-based-lighting and light-probe baker", "iblbake"};
    app.require_subcommand(1);
    app.set_version_flag("--version", "iblbake " IBLBAKE_VERSION);

    std::map<const CLI::App*, ibl::cli::Action> actions;
    auto add = [&](ibl::cli::Action action) { actions[app.get_subcommands({}).back()] = std::move(action); };
    add(ibl::cli::addDevicesCommand(app));
    add(ibl::cli::addDfgCommand(app));
    add(ibl::cli::addSpecularCommand(app));
    add(ibl::cli::addDiffuseCommand(app));
    add(ibl::cli::addInspectCommand(app));
    add(ibl::cli::addCalibrateCommand(app));
    add(ibl::cli::addPreviewCommand(app));

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
    } catch (const ibl::Error& e) {
        std::fprintf(stderr, "iblbake: error: %s\n", e.what());
        return 1;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "iblbake: internal error: %s\n", e.what());
        return 3;
    }
}
