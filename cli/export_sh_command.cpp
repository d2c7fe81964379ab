// iblbake export-sh BAKE_DIR --profile filament -o sh.txt: the bake's diffuse SH in an engine's own
// convention (iblbake/baker/filament_export.h exportFilamentSh).
#include "commands.h"

#include <iblbake/baker/filament_export.h>

#include <cstdio>

namespace ibl::cli {
namespace {

struct ExportShOptions {
    std::string bakeDir;
    std::string output;
    std::string profile;
};

} // namespace

Action addExportShCommand(CLI::App& app) {
    auto [o, cmd] = addSubcommand<ExportShOptions>(app, "export-sh",
                                                   "write a bake's diffuse SH in an engine's convention");
    cmd->add_option("bake", o->bakeDir, "bake directory holding diffuse.json")->required();
    cmd->add_option("-o,--output", o->output, "output file")->required();
    cmd->add_option("--profile", o->profile,
                    "filament: cmgen's sh.txt (irradiance / pi, pre-scaled by the SH basis constants)")
        ->required()
        ->check(CLI::IsMember({"filament"}));

    return [o = o] {
        const std::filesystem::path diffuse = exportFilamentSh(o->bakeDir, o->output);
        std::printf("wrote   %s (Filament sh.txt from %s)\n", o->output.c_str(), diffuse.c_str());
        return 0;
    };
}

} // namespace ibl::cli
