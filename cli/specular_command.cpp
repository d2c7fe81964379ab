// iblbake specular: HDRI in, prefiltered specular (LD) cube mip chain out as KTX2. The flow is the
// library's: the plan of a scene's environment, sun and specular stages (iblbake/baker/product_plans.h
// specularPlan), run by the scene's stage runner; this parses and prints.
#include "calibration_options.h"
#include "commands.h"
#include "common_options.h"
#include "input_options.h"

#include <iblbake/baker/product_plans.h>
#include <iblbake/core/limits.h>

#include <chrono>
#include <cstdio>
#include <optional>

namespace ibl::cli {

namespace {

struct SpecularOptions {
    InputOptions input;
    std::string output;
    int size = 256;
    int levels = 0;
    std::string quality = "production";
    std::uint32_t samples = 0;
    CubeStorageOptions storage;
    std::string exrDir;
    std::string preview;
    std::string roughLayers;
    std::string mipMapping = "frostbite";
    float lodBias = SpecularSettings{}.lodBias;
    BackendOptions backend;
    CalibrationOptions calibration;
};

// The library's job of these options.
SpecularJob specularJob(const SpecularOptions& o) {
    return {.settings = {.levels = o.levels,
                         .mapping = parseMipMapping(o.mipMapping),
                         .samples = o.samples,
                         .quality = parseQuality(o.quality),
                         .lodBias = o.lodBias},
            .format = o.storage.format,
            .clampToFormat = o.storage.clampToFormat,
            .profile = o.storage.profile,
            .chain = o.output,
            .roughLayers = o.roughLayers,
            .exrDirectory = o.exrDir,
            .preview = o.preview};
}

} // namespace

Action addSpecularCommand(CLI::App& app) {
    auto [o, cmd] = addInputSubcommand<SpecularOptions>(
        app, "specular", "bake the prefiltered specular (LD) cube mip chain to KTX2", "output .ktx2 file");
    cmd->add_option("--size", o->size, "face size of level 0 (power of two)")->capture_default_str();
    cmd->add_option("--levels", o->levels, "mip levels (default: down to 1x1)")
        ->check(CLI::Range(1, mipLevelCount(limits::kMaxFaceSize)));
    addQualityOption(*cmd, o->quality, "the chain");
    cmd->add_option("--samples", o->samples, "maximum samples per texel (overrides the preset)")
        ->check(CLI::Range(1u, limits::kMaxSamples));
    o->storage.addTo(*cmd, "chain");
    cmd->add_option("--exr", o->exrDir, "also write every level as OpenEXR into this directory");
    cmd->add_option("--preview", o->preview, "also write a tone-mapped PNG of every level");
    cmd->add_option(
        "--rough-layers", o->roughLayers,
        "also write the chain's rough layers (KTX2 cube map array, docs/formats.md \"Rough layers\")");
    cmd->add_option("--mip-mapping", o->mipMapping, "roughness per level: frostbite (eq. 63) or linear")
        ->capture_default_str()
        ->check(CLI::IsMember(std::vector<std::string>(kMipMappingNames.begin(), kMipMappingNames.end())));
    cmd->add_option("--lod-bias", o->lodBias, "added to the source LOD of each sample")
        ->capture_default_str();
    o->backend.addTo(*cmd);
    o->calibration.addTo(*cmd);

    return [o = o] {
        auto start = std::chrono::steady_clock::now();
        const SpecularJob job = specularJob(*o);
        validateSpecularSettings(job.settings, o->size);
        const Backend backend = standaloneSpecularBackend(parseBackend(o->backend.backend),
                                                          !o->backend.device.empty(), job.settings, o->size);
        const ProductPlan plan =
            specularPlan(environmentJob(o->input, o->calibration, o->size), job, backendName(backend));
        return runProductCommand(
            plan, o->calibration, o->backend, backend, "specular",
            [&](const ProductRun& run) { return specularRunText(plan, run); }, start);
    };
}

} // namespace ibl::cli
