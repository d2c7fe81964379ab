// iblbake dfg: bakes the DFG / diffuse LUT to OpenEXR: the plan of a scene's dfg-lut stage with the
// command's settings (iblbake/baker/product_plans.h dfgPlan), run by the scene's stage runner.
#include "commands.h"
#include "common_options.h"

#include <iblbake/baker/product_plans.h>

#include <cstdio>
#include <optional>

namespace ibl::cli {

namespace {
struct DfgOptions {
    std::string output;
    DfgSettings settings;
    bool half = false;
    BackendOptions backend;
};
} // namespace

Action addDfgCommand(CLI::App& app) {
    auto [opts, cmd] = addSubcommand<DfgOptions>(
        app, "dfg", "bake the DFG / diffuse LUT (R = DFG1, G = DFG2, B = Disney diffuse)");
    cmd->add_option("-o,--output", opts->output, "output OpenEXR file")->required();
    cmd->add_option("--size", opts->settings.size, "texels per side (x: NoV, y: perceptual roughness)")
        ->capture_default_str()
        ->check(CLI::Range(1, 8192));
    cmd->add_option("--samples", opts->settings.sampleCount, "samples per texel")
        ->capture_default_str()
        ->check(CLI::Range(1, 1 << 24));
    auto* half = cmd->add_flag("--half", opts->half, "store half floats");
    cmd->add_flag("--float,!--no-half", opts->half, "store 32-bit floats (default)")->excludes(half);
    opts->backend.addTo(*cmd);

    return [opts = opts] {
        const Backend backend =
            standaloneDfgBackend(parseBackend(opts->backend.backend), !opts->backend.device.empty());
        std::optional<Executor> executor;
        const ProductRun run =
            runProductPlan(dfgPlan(opts->settings, opts->half ? DfgLutFile::ExrHalf : DfgLutFile::ExrFloat,
                                   opts->output, backendName(backend)),
                           [&] { return &executor.emplace(opts->backend.makeExecutor(backend)); });
        BackendOptions::storeBuiltKernels(*executor);
        const double ms = 1000.0 * run.stageSeconds("dfg");
        std::printf("wrote %s (%ux%u DFG LUT, %u samples/texel, %s, %.1f ms)\n", opts->output.c_str(),
                    opts->settings.size, opts->settings.size, opts->settings.sampleCount,
                    executor->description().c_str(), ms);
        opts->backend.printTiming(*executor, "dfg", ms);
        return 0;
    };
}

} // namespace ibl::cli
