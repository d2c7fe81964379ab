// iblbake specular: HDRI in, prefiltered specular (LD) cube mip chain out as KTX2. The flow is the
// library's (iblbake/baker/product_flows.h bakeSpecularProducts); this parses, prepares and prints.
#include "calibration_options.h"
#include "commands.h"
#include "common_options.h"
#include "input_options.h"

#include <iblbake/baker/product_flows.h>
#include <iblbake/core/limits.h>
#include <iblbake/ktx2/cube_profile.h>

#include <chrono>
#include <cstdio>
#include <memory>

namespace ibl::cli {

namespace {

struct SpecularOptions {
    InputOptions input;
    std::string output;
    int size = 256;
    int levels = 0;
    std::string quality = "production";
    std::uint32_t samples = 0;
    std::string format = "rgba16f";
    std::string profile = "standard";
    std::string exrDir;
    std::string preview;
    std::string roughLayers;
    std::string mipMapping = "frostbite";
    float lodBias = SpecularSettings{}.lodBias;
    bool clampToFormat = false;
    BackendOptions backend;
    CalibrationOptions calibration;
};

// The library's job of these options.
SpecularJob specularJob(const SpecularOptions& o) {
    SpecularJob job;
    job.settings.levels = o.levels;
    job.settings.quality = parseQuality(o.quality);
    job.settings.samples = o.samples;
    job.settings.mapping = parseMipMapping(o.mipMapping);
    job.settings.lodBias = o.lodBias;
    job.faceSize = o.size;
    job.rotateDegrees = o.input.rotateDegrees;
    job.format = parseKtx2Format(o.format);
    job.clampToFormat = o.clampToFormat;
    job.profile = o.profile;
    job.sunMaxSolidAngle = o.calibration.sunMaxSolidAngle;
    job.chain = o.output;
    job.roughLayers = o.roughLayers;
    job.exrDirectory = o.exrDir;
    job.preview = o.preview;
    job.sunJson = o.calibration.sunJson;
    return job;
}

} // namespace

Action addSpecularCommand(CLI::App& app) {
    auto o = std::make_shared<SpecularOptions>();
    CLI::App* cmd =
        app.add_subcommand("specular", "bake the prefiltered specular (LD) cube mip chain to KTX2");
    o->input.addTo(*cmd);
    cmd->add_option("-o,--output", o->output, "output .ktx2 file")->required();
    cmd->add_option("--size", o->size, "face size of level 0 (power of two)")->capture_default_str();
    cmd->add_option("--levels", o->levels, "mip levels (default: down to 1x1)")
        ->check(CLI::Range(1, mipLevelCount(limits::kMaxFaceSize)));
    cmd->add_option("--quality", o->quality, "sample preset: draft, production, reference")
        ->capture_default_str()
        ->check(CLI::IsMember({"draft", "production", "reference"}));
    cmd->add_option("--samples", o->samples, "maximum samples per texel (overrides the preset)")
        ->check(CLI::Range(1u, limits::kMaxSamples));
    cmd->add_option("--format", o->format, "rgba16f, rgba32f, b10g11r11, e5b9g9r9")
        ->capture_default_str()
        ->check(CLI::IsMember(kKtx2FormatNames));
    cmd->add_option("--profile", o->profile,
                    "cube layout for the engine: standard (OpenGL faces), three (three.js CubeTexture)")
        ->capture_default_str()
        ->check(CLI::IsMember(kCubeProfileNames));
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
    cmd->add_flag("--clamp-to-format", o->clampToFormat,
                  "clamp to the format's range (energy lost is reported) instead of storing with a storage "
                  "scale");
    o->backend.addTo(*cmd);
    o->calibration.addTo(*cmd);

    return [o] {
        auto start = std::chrono::steady_clock::now();
        const SpecularJob job = specularJob(*o);
        validateSpecularSettings(job.settings, o->size);
        checkSpecularOutputs(job); // every output before any work: a bad --preview must not fail after -o
        std::future<Executor> pendingExecutor = o->backend.startExecutor(standaloneSpecularBackend(
            parseBackend(o->backend.backend), !o->backend.device.empty(), job.settings, o->size));
        // The cube with the sun is kept for level 0.
        PreparedEnvironment input = ingestCalibrated(o->input, o->calibration, o->size, true);
        const Executor executor = pendingExecutor.get();
        const double ingestMs = millisecondsSince(start);

        const SpecularProducts products =
            bakeSpecularProducts(std::move(input), job, executor, [&](const char* stage, double ms) {
                o->backend.printTiming(executor, stage, ms);
            });
        BackendOptions::storeBuiltKernels(executor);
        for (const SpecularLevelTiming& t : products.timings)
            std::printf("level %2d  r=%.4f  %4d px  %8.2f ms\n", t.level, t.perceptualRoughness,
                        products.levelFaceSizes[std::size_t(t.level)], t.milliseconds);
        const StoredCube& chain = products.written.chain;
        std::printf("wrote   %s: %zu levels, %s, %llu clamped texels, %llu repaired non-finite\n",
                    o->output.c_str(), products.levelFaceSizes.size(), o->format.c_str(),
                    (unsigned long long)chain.stats.clampedTexels,
                    (unsigned long long)chain.stats.repairedNonFinite);
        printStorage(o->output, o->format, chain.storage);
        if (products.written.roughLayers) {
            std::printf("wrote   %s: %u rough layers of %u px (r = %s)\n", o->roughLayers.c_str(),
                        IBL_ROUGH_LAYER_COUNT, roughLayerFaceSize(std::uint32_t(o->size)),
                        roughLayerRoughnessText().c_str());
            printStorage(o->roughLayers, o->format, products.written.roughLayers->storage);
        }
        std::printf("time    ingest %.1f ms, bake %.1f ms (%s), total %.1f ms\n", ingestMs,
                    products.bakeMilliseconds, executor.description().c_str(), millisecondsSince(start));
        return 0;
    };
}

} // namespace ibl::cli
