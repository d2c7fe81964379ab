// iblbake diffuse: HDRI in, L2 SH (radiance and pre-scaled irradiance) out as JSON, optionally a small
// irradiance cube as KTX2. The flow is the library's: the plan of a scene's environment, sun, diffuse and
// irradiance stages (iblbake/baker/product_plans.h diffusePlan); this parses and prints.
#include "calibration_options.h"
#include "commands.h"
#include "common_options.h"
#include "input_options.h"

#include <iblbake/baker/product_plans.h>
#include <iblbake/core/error.h>
#include <iblbake/core/limits.h>

#include <cstdio>
#include <filesystem>
#include <optional>

namespace ibl::cli {

namespace {

struct DiffuseOptions {
    InputOptions input;
    std::string output;
    std::string irradianceCube;
    int irradianceSize = 32;
    std::string irradianceMethod = "sampled";
    std::string quality = "production";
    std::uint32_t samples = 0;
    std::string window = "auto";
    std::optional<double> windowParam;
    CubeStorageOptions storage;
    int size = 256;
    BackendOptions backend;
    CalibrationOptions calibration;

    DiffuseJob job() const; // the library's job of these options
};

DiffuseJob DiffuseOptions::job() const {
    DiffuseJob job;
    job.window = {.automatic = window == "auto", .parameter = windowParam};
    job.document = output;
    if (!job.window.automatic) job.window.window = parseShWindow(window);
    if (irradianceCube.empty()) return job;
    job.cube = {
        .method = parseIrradianceMethod(irradianceMethod),
        .settings = {.faceSize = irradianceSize, .samples = samples, .quality = parseQuality(quality)},
        .format = storage.format,
        .clampToFormat = storage.clampToFormat,
        .profile = storage.profile,
        .file = irradianceCube};
    return job;
}

} // namespace

Action addDiffuseCommand(CLI::App& app) {
    auto [o, cmd] = addInputSubcommand<DiffuseOptions>(
        app, "diffuse",
        "bake diffuse lighting: L2 SH (radiance + pre-scaled irradiance) to JSON, irradiance cube",
        "output .json file (SH coefficients and report)");
    cmd->add_option("--irradiance-cube", o->irradianceCube,
                    "also write the irradiance cube (stores E/pi) to this .ktx2 file");
    cmd->add_option("--irradiance-size", o->irradianceSize, "face size of the irradiance cube")
        ->capture_default_str()
        ->check(CLI::Range(1, 4096));
    cmd->add_option("--irradiance-method", o->irradianceMethod,
                    "sampled (cosine importance sampling, exact suns) or sh (evaluate the windowed SH)")
        ->capture_default_str()
        ->check(CLI::IsMember({"sampled", "sh"}));
    addQualityOption(*cmd, o->quality, "the sampled cube");
    cmd->add_option("--samples", o->samples, "cosine samples per texel (overrides the preset)")
        ->check(CLI::Range(1u, limits::kMaxSamples));
    cmd->add_option(
           "--window", o->window,
           "SH deringing window: auto (weakest with E >= 0 everywhere), none, sloan, hanning, lanczos")
        ->capture_default_str()
        ->check(CLI::IsMember({"auto", "none", "sloan", "hanning", "lanczos"}));
    cmd->add_option("--window-param", o->windowParam,
                    "window parameter: sloan lambda >= 0, hanning/lanczos width w > 0 in bands (default: the "
                    "weakest value with E >= 0 everywhere)");
    o->storage.addTo(*cmd, "irradiance cube");
    cmd->add_option("--size", o->size,
                    "face size of the source cube (power of two for --irradiance-method sampled)")
        ->capture_default_str()
        ->check(CLI::Range(1, limits::kMaxFaceSize));
    o->backend.addTo(*cmd);
    o->calibration.addTo(*cmd);

    return [o = o] {
        auto start = std::chrono::steady_clock::now();
        const DiffuseJob job = o->job();
        // Only the sampled irradiance cube runs on the backend; the SH are projected on the CPU.
        const bool needsBackend = job.cube && job.cube->method == IrradianceMethod::Sampled;
        const Backend backend = parseBackend(o->backend.backend);
        const ProductPlan plan = diffusePlan(environmentJob(o->input, o->calibration, o->size), job,
                                             needsBackend ? backendName(backend) : "none");
        return runProductCommand(
            plan, o->calibration, o->backend, needsBackend ? std::optional(backend) : std::nullopt,
            "irradiance", [&](const ProductRun& run) { return diffuseRunText(plan, run); }, start);
    };
}

} // namespace ibl::cli
