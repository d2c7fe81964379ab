// iblbake dfg: bakes the DFG / diffuse LUT to OpenEXR.
#include "commands.h"
#include "common_options.h"

#include <iblbake/baker/product_writers.h>
#include <iblbake/ktx2/atomic_file.h>

#include <chrono>
#include <cstdio>
#include <memory>

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
    auto opts = std::make_shared<DfgOptions>();
    CLI::App* cmd =
        app.add_subcommand("dfg", "bake the DFG / diffuse LUT (R = DFG1, G = DFG2, B = Disney diffuse)");
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

    return [opts] {
        checkOutputFile(opts->output); // before the work
        Executor executor = opts->backend.makeExecutor(
            standaloneDfgBackend(parseBackend(opts->backend.backend), !opts->backend.device.empty()));
        auto start = std::chrono::steady_clock::now();
        ImageRGBA lut = bakeDfgLut(opts->settings, executor);
        double ms =
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();

        OutputSet outputs;
        writeDfgLutProduct(outputs, lut, opts->settings.sampleCount,
                           opts->half ? DfgLutFile::ExrHalf : DfgLutFile::ExrFloat, opts->output);
        outputs.commit();
        BackendOptions::storeBuiltKernels(executor);
        std::printf("wrote %s (%ux%u DFG LUT, %u samples/texel, %s, %.1f ms)\n", opts->output.c_str(),
                    opts->settings.size, opts->settings.size, opts->settings.sampleCount,
                    executor.description().c_str(), ms);
        opts->backend.printTiming(executor, "dfg", ms);
        return 0;
    };
}

} // namespace ibl::cli
