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
#include <iblbake/ktx2/cube_profile.h>

#include <cstdio>
#include <filesystem>
#include <memory>
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
    std::string format = "rgba16f";
    bool clampToFormat = false;
    std::string profile = "standard";
    int size = 256;
    BackendOptions backend;
    CalibrationOptions calibration;

    // The job of these options; throws ibl::Error naming the flag of an impossible combination.
    DiffuseJob job() const;
};

DiffuseJob DiffuseOptions::job() const {
    DiffuseJob job;
    const IrradianceMethod method = parseIrradianceMethod(irradianceMethod);
    if (!irradianceCube.empty() && method == IrradianceMethod::Sampled && (size & (size - 1)) != 0)
        throw Error("--size: " + std::to_string(size) +
                    " is not a power of two (needed by --irradiance-method sampled)");
    job.window.automatic = window == "auto";
    if (!job.window.automatic) job.window.window = parseShWindow(window);
    job.window.parameter = windowParam;
    if (windowParam && (job.window.automatic || job.window.window == ShWindow::None))
        throw Error("--window-param: needs --window sloan, hanning or lanczos");
    job.document = output;
    if (irradianceCube.empty()) return job;
    if (std::filesystem::absolute(irradianceCube) == std::filesystem::absolute(output))
        throw Error("--irradiance-cube: " + irradianceCube + " is also the JSON output");
    job.cube = {
        .method = method,
        .settings = {.faceSize = irradianceSize, .samples = samples, .quality = parseQuality(quality)},
        .format = format,
        .clampToFormat = clampToFormat,
        .profile = profile,
        .file = irradianceCube};
    return job;
}

} // namespace

Action addDiffuseCommand(CLI::App& app) {
    auto o = std::make_shared<DiffuseOptions>();
    CLI::App* cmd = app.add_subcommand(
        "diffuse",
        "bake diffuse lighting: L2 SH (radiance + pre-scaled irradiance) to JSON, irradiance cube");
    o->input.addTo(*cmd);
    cmd->add_option("-o,--output", o->output, "output .json file (SH coefficients and report)")->required();
    cmd->add_option("--irradiance-cube", o->irradianceCube,
                    "also write the irradiance cube (stores E/pi) to this .ktx2 file");
    cmd->add_option("--irradiance-size", o->irradianceSize, "face size of the irradiance cube")
        ->capture_default_str()
        ->check(CLI::Range(1, 4096));
    cmd->add_option("--irradiance-method", o->irradianceMethod,
                    "sampled (cosine importance sampling, exact suns) or sh (evaluate the windowed SH)")
        ->capture_default_str()
        ->check(CLI::IsMember({"sampled", "sh"}));
    cmd->add_option("--quality", o->quality,
                    "sample preset of the sampled cube: draft, production, reference")
        ->capture_default_str()
        ->check(CLI::IsMember({"draft", "production", "reference"}));
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
    cmd->add_option(
           "--format", o->format,
           "irradiance cube format: rgba16f, rgba32f, b10g11r11, e5b9g9r9, bc6h, bc6h-fast, bc6h-best "
           "(docs/formats.md \"Storage formats\"); --irradiance-cube NAME.dds writes DDS")
        ->capture_default_str()
        ->check(CLI::IsMember(kKtx2FormatNames));
    cmd->add_flag("--clamp-to-format", o->clampToFormat,
                  "clamp the irradiance cube to its format's range (energy lost is reported) instead of "
                  "storing it with a storage scale");
    cmd->add_option("--profile", o->profile,
                    "irradiance cube layout: standard (OpenGL faces), three (three.js CubeTexture)")
        ->capture_default_str()
        ->check(CLI::IsMember(kCubeProfileNames));
    cmd->add_option("--size", o->size,
                    "face size of the source cube (power of two for --irradiance-method sampled)")
        ->capture_default_str()
        ->check(CLI::Range(1, limits::kMaxFaceSize));
    o->backend.addTo(*cmd);
    o->calibration.addTo(*cmd);

    return [o] {
        auto start = std::chrono::steady_clock::now();
        const DiffuseJob job = o->job();
        // Only the sampled irradiance cube runs on the backend; the SH are projected on the CPU.
        const bool needsBackend = job.cube && job.cube->method == IrradianceMethod::Sampled;
        const Backend backend = parseBackend(o->backend.backend);
        std::future<Executor> pendingExecutor;
        if (needsBackend) pendingExecutor = o->backend.startExecutor(backend);
        std::optional<Executor> executor;
        const ProductPlan plan = diffusePlan(environmentJob(o->input, o->calibration, o->size), job,
                                             needsBackend ? backendName(backend) : "none");
        const ProductRun run = runCalibrated(plan, o->calibration, [&] {
            return &executor.emplace(pendingExecutor.get()); // its set-up overlapped the ingest
        });
        std::printf("%s", environmentRunText(run).c_str());
        if (executor) {
            o->backend.printTiming(*executor, "irradiance-cube", 1000.0 * run.stageSeconds("irradiance"));
            BackendOptions::storeBuiltKernels(*executor);
        }
        std::printf("%s", diffuseRunText(plan, run).c_str());
        std::printf("time    ingest %.1f ms, sh %.1f ms, cube %.1f ms (%s), total %.1f ms\n",
                    1000.0 * (run.stageSeconds("environment") + run.stageSeconds("sun")),
                    1000.0 * run.stageSeconds("diffuse"), 1000.0 * run.stageSeconds("irradiance"),
                    executor ? executor->description().c_str() : "cpu", millisecondsSince(start));
        return 0;
    };
}

} // namespace ibl::cli
