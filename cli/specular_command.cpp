// iblbake specular: HDRI in, prefiltered specular (LD) cube mip chain out as KTX2. The flow is the
// library's: the plan of a scene's environment, sun and specular stages (iblbake/baker/product_plans.h
// specularPlan), run by the scene's stage runner; this parses and prints.
#include "calibration_options.h"
#include "commands.h"
#include "common_options.h"
#include "input_options.h"

#include <iblbake/baker/product_plans.h>
#include <iblbake/core/limits.h>
#include <iblbake/ktx2/cube_profile.h>

#include <chrono>
#include <cstdio>
#include <memory>
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
    return {.settings = {.levels = o.levels,
                         .mapping = parseMipMapping(o.mipMapping),
                         .samples = o.samples,
                         .quality = parseQuality(o.quality),
                         .lodBias = o.lodBias},
            .format = o.format,
            .clampToFormat = o.clampToFormat,
            .profile = o.profile,
            .chain = o.output,
            .roughLayers = o.roughLayers,
            .exrDirectory = o.exrDir,
            .preview = o.preview};
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
    cmd->add_option("--format", o->format,
                    "rgba16f, rgba32f, b10g11r11, e5b9g9r9, or BC6H made by the default, fast or best preset "
                    "(docs/formats.md \"Storage formats\"); -o NAME.dds writes DDS")
        ->capture_default_str()
        ->check(CLI::IsMember(kKtx2FormatNames));
    cmd->add_option("--profile", o->profile, "standard (OpenGL faces) or three (three.js r187's own PMREM)")
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
        const Backend backend = standaloneSpecularBackend(parseBackend(o->backend.backend),
                                                          !o->backend.device.empty(), job.settings, o->size);
        std::future<Executor> pendingExecutor = o->backend.startExecutor(backend);
        std::optional<Executor> executor;
        const ProductPlan plan =
            specularPlan(environmentJob(o->input, o->calibration, o->size), job, backendName(backend));
        const ProductRun run = runCalibrated(plan, o->calibration, [&] {
            return &executor.emplace(pendingExecutor.get()); // its set-up overlapped the ingest
        });
        std::printf("%s", environmentRunText(run).c_str());
        const double bakeMs = 1000.0 * run.stageSeconds("specular");
        o->backend.printTiming(*executor, "specular", bakeMs);
        BackendOptions::storeBuiltKernels(*executor);
        std::printf("%s", specularRunText(plan, run).c_str());
        std::printf("time    ingest %.1f ms, bake %.1f ms (%s), total %.1f ms\n",
                    1000.0 * (run.stageSeconds("environment") + run.stageSeconds("sun")), bakeMs,
                    executor->description().c_str(), millisecondsSince(start));
        return 0;
    };
}

} // namespace ibl::cli
