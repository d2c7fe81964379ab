// iblbake lightcard: bakes a texture into a light card for a textured rectangle light (KTX2 2D array).
#include "commands.h"
#include "common_options.h"

#include <iblbake/baker/light_card.h>

#include <chrono>
#include <cstdio>

namespace ibl::cli {

namespace {
struct LightCardOptions {
    std::string texture, output, format = "rgba16f";
    LightCardSettings settings;
    BackendOptions backend;
};
} // namespace

Action addLightCardCommand(CLI::App& app) {
    auto [opts, cmd] = addSubcommand<LightCardOptions>(
        app, "lightcard",
        "bake a texture into a light card (layer 0: specular mips by footprint, layers 1..K: "
        "diffuse by distance)");
    cmd->add_option("TEXTURE", opts->texture, "the light's emission (any image format; 8-bit files are sRGB)")
        ->required();
    cmd->add_option("-o,--output", opts->output, "output KTX2 file")->required();
    cmd->add_option("--size", opts->settings.size, "level-0 texels per side (a power of two, 4 to 4096)")
        ->capture_default_str();
    cmd->add_option("--layers", opts->settings.diffuseLayers, "diffuse layers by distance (2 to 64)")
        ->capture_default_str();
    cmd->add_option("--format", opts->format, "rgba16f, rgba32f, b10g11r11, e5b9g9r9")->capture_default_str();
    opts->backend.addTo(*cmd);

    return [opts = opts] {
        opts->settings.format = parseKtx2Format(opts->format);
        Executor executor = opts->backend.makeExecutor();
        auto start = std::chrono::steady_clock::now();
        const Ktx2WriteStats stats = bakeLightCardFile(opts->texture, opts->output, opts->settings, executor);
        const double ms = millisecondsSince(start);
        BackendOptions::storeBuiltKernels(executor);
        std::printf("wrote %s (%dx%d light card, %d diffuse layers, %s, %.1f ms)\n", opts->output.c_str(),
                    opts->settings.size, opts->settings.size, opts->settings.diffuseLayers,
                    executor.description().c_str(), ms);
        if (stats.clampedTexels > 0)
            std::fprintf(stderr, "warning: %s: %llu texels clamped to %s's range\n", opts->output.c_str(),
                         static_cast<unsigned long long>(stats.clampedTexels), opts->format.c_str());
        opts->backend.printTiming(executor, "lightcard", ms);
        return 0;
    };
}

} // namespace ibl::cli
