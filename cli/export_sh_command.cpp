// iblbake export-sh BAKE_DIR --profile filament -o sh.txt: the bake's diffuse SH in an engine's own
// convention (iblbake/baker/filament_sh.h).
#include "commands.h"

#include <iblbake/baker/filament_sh.h>
#include <iblbake/baker/gltf_export.h>
#include <iblbake/core/error.h>
#include <iblbake/ktx2/atomic_file.h>

#include <cstdio>
#include <memory>

namespace ibl::cli {
namespace {

struct ExportShOptions {
    std::string bakeDir;
    std::string output;
    std::string profile;
};

} // namespace

Action addExportShCommand(CLI::App& app) {
    auto o = std::make_shared<ExportShOptions>();
    CLI::App* cmd = app.add_subcommand("export-sh", "write a bake's diffuse SH in an engine's convention");
    cmd->add_option("bake", o->bakeDir, "bake directory holding diffuse.json")->required();
    cmd->add_option("-o,--output", o->output, "output file")->required();
    cmd->add_option("--profile", o->profile,
                    "filament: cmgen's sh.txt (irradiance / pi, pre-scaled by the SH basis constants)")
        ->required()
        ->check(CLI::IsMember({"filament"}));

    return [o] {
        const std::filesystem::path diffuse = std::filesystem::path(o->bakeDir) / "diffuse.json";
        const std::string text = filamentShText(readPrescaledIrradiance(diffuse));
        AtomicFile file(o->output);
        writeFileBytes(file.tempPath(), text, o->output);
        file.commit();
        std::printf("wrote   %s (Filament sh.txt from %s)\n", o->output.c_str(), diffuse.c_str());
        return 0;
    };
}

} // namespace ibl::cli
