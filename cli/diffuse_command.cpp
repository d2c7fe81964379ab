// iblbake diffuse: HDRI in, L2 SH (radiance and pre-scaled irradiance) out as JSON, optionally a small
// irradiance cube as KTX2.
#include "calibration_options.h"
#include "commands.h"
#include "common_options.h"
#include "input_options.h"

#include <iblbake/baker/ingest.h>
#include <iblbake/baker/irradiance.h>
#include <iblbake/baker/products.h>
#include <iblbake/baker/sh.h>
#include <iblbake/core/error.h>
#include <iblbake/core/limits.h>
#include <iblbake/ktx2/atomic_file.h>
#include <iblbake/ktx2/cube_profile.h>
#include <iblbake/ktx2/ktx2.h>
#include <iblbake/ktx2/output_set.h>

#include <nlohmann/json.hpp>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
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
};

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
    cmd->add_option("--format", o->format, "irradiance cube format: rgba16f, rgba32f, b10g11r11, e5b9g9r9")
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
        ->capture_default_str();
    o->backend.addTo(*cmd);
    o->calibration.addTo(*cmd);

    return [o] {
        auto start = std::chrono::steady_clock::now();
        const bool wantCube = !o->irradianceCube.empty();
        const IrradianceMethod method = parseIrradianceMethod(o->irradianceMethod);
        const Ktx2Format format = parseKtx2Format(o->format);
        if (o->size < 1 || o->size > limits::kMaxFaceSize)
            throw Error("--size: " + std::to_string(o->size) + " is not from 1 to " +
                        std::to_string(limits::kMaxFaceSize));
        if (wantCube && method == IrradianceMethod::Sampled && (o->size & (o->size - 1)) != 0)
            throw Error("--size: " + std::to_string(o->size) +
                        " is not a power of two (needed by --irradiance-method sampled)");
        ShWindowSettings window;
        window.automatic = o->window == "auto";
        if (!window.automatic) window.window = parseShWindow(o->window);
        window.parameter = o->windowParam;
        if (o->windowParam && (window.automatic || window.window == ShWindow::None))
            throw Error("--window-param: needs --window sloan, hanning or lanczos");
        if (wantCube && std::filesystem::absolute(o->irradianceCube) == std::filesystem::absolute(o->output))
            throw Error("--irradiance-cube: " + o->irradianceCube + " is also the JSON output");
        // Fail on unwritable outputs before the work; the files appear only when everything succeeded.
        checkOutputFile(o->output);
        if (wantCube) checkOutputFile(o->irradianceCube);
        if (!o->calibration.sunJson.empty()) checkOutputFile(o->calibration.sunJson);
        OutputSet outputs;

        // Only the sampled irradiance cube runs on the backend; the SH are projected on the CPU.
        const bool needsBackend = wantCube && method == IrradianceMethod::Sampled;
        std::future<Executor> pendingExecutor;
        if (needsBackend) pendingExecutor = o->backend.startExecutor();
        const PreparedEnvironment input = ingestCalibrated(o->input, o->calibration, o->size);
        const Executor executor = needsBackend ? pendingExecutor.get() : Executor::cpu();
        const SourceEnvironment& env = input.env;
        const PreparedEnvironment& calibration = input;
        const double ingestMs = millisecondsSince(start);
        const IngestReport& r = env.report;

        auto shStart = std::chrono::steady_clock::now();
        DiffuseSH sh = bakeDiffuseSH(env.cube, window);
        const double shMs = millisecondsSince(shStart);
        const ShWindowResult& w = sh.window;
        auto percent = [&](const glm::dvec3& v) { // the worst channel, relative to its mean irradiance
            double worst = std::numeric_limits<double>::infinity();
            for (int c = 0; c < 3; ++c)
                if (w.meanIrradiance[c] > 0.0) worst = std::min(worst, v[c] / w.meanIrradiance[c]);
            return std::isfinite(worst) ? 100.0 * worst : 0.0;
        };
        std::printf("sh      L2 from %d px faces; window %s", env.cube.faceSize, shWindowName(w.window));
        if (w.window != ShWindow::None)
            std::printf(" %s=%.6g", w.window == ShWindow::Sloan ? "lambda" : "w", w.parameter);
        std::printf(" (%s), band factors %.4f %.4f\n", w.searched ? "searched" : "given", w.factors[1],
                    w.factors[2]);
        std::printf("        min irradiance before %.6g %.6g %.6g, after %.6g %.6g %.6g "
                    "(worst channel: %.3f%% -> %.3f%% of its mean)\n",
                    w.minBefore.x, w.minBefore.y, w.minBefore.z, w.minAfter.x, w.minAfter.y, w.minAfter.z,
                    percent(w.minBefore), percent(w.minAfter));
        o->backend.printTiming(executor, "sh-projection", shMs);

        nlohmann::json cubeJson;
        double cubeMs = 0.0;
        if (wantCube) {
            auto cubeStart = std::chrono::steady_clock::now();
            IrradianceSettings settings;
            settings.faceSize = o->irradianceSize;
            settings.quality = parseQuality(o->quality);
            settings.samples = o->samples;
            CubeMap cube;
            std::uint64_t shClamped = 0;
            if (method == IrradianceMethod::Sampled)
                cube = bakeIrradianceCube(env.cube, settings, executor);
            else
                cube = irradianceCubeFromSH(sh.irradiance, o->irradianceSize, &shClamped);
            cubeMs = millisecondsSince(cubeStart);
            const std::string methodText = irradianceMethodText(method, irradianceSamplesFor(settings));
            Ktx2KeyValues kv = irradianceKeyValues(methodText, r.workingColorSpace,
                                                   std::filesystem::path(r.file).filename().string(),
                                                   r.latLongPixels, calibration.record, calibration.sun);
            kv.emplace_back(kCubeProfileKey, o->profile);
            CubeMapChain chain;
            chain.levels.push_back(std::move(cube));
            const ProductStorage storage = chooseProductStorage(chain, format, o->clampToFormat);
            Ktx2WriteStats stats;
            outputs.writeFile(o->irradianceCube, [&](const std::filesystem::path& temporary) {
                stats = writeProductCube(temporary, chain, format, kv, storage);
            });
            std::printf("cube    %d px %s, %s: %.1f ms, %llu clamped texels, %llu SH-negative texels\n",
                        o->irradianceSize, o->irradianceMethod.c_str(), o->format.c_str(), cubeMs,
                        (unsigned long long)stats.clampedTexels, (unsigned long long)shClamped);
            printStorage(o->irradianceCube, o->format, storage);
            cubeJson = {{"file", o->irradianceCube},
                        {"faceSize", o->irradianceSize},
                        {"format", o->format},
                        {"method", irradianceMethodName(method)},
                        {"methodDetail", methodText},
                        {"normalization", kIrradianceNormalization},
                        {"clampedTexels", stats.clampedTexels},
                        {"shNegativeTexels", shClamped}};
            cubeJson.update(productStorageToJson(storage));
            if (method == IrradianceMethod::Sampled) cubeJson["samples"] = irradianceSamplesFor(settings);
            o->backend.printTiming(executor, "irradiance-cube", cubeMs);
        }

        const DiffuseSource source{r.file,
                                   r.width,
                                   r.height,
                                   layoutName(r.layout),
                                   r.inputColorSpace,
                                   env.cube.faceSize,
                                   o->input.rotateDegrees,
                                   r.latLongPixels};
        nlohmann::json doc =
            diffuseDocument(sh, o->window, r.workingColorSpace, source, calibration.record, calibration.sun);
        doc["timing"] = {{"ingestMs", ingestMs}, {"shMs", shMs}, {"irradianceCubeMs", cubeMs}};
        if (wantCube) doc["irradianceCube"] = cubeJson;

        outputs.writeFile(o->output, [&](const std::filesystem::path& temporary) {
            writeFileBytes(temporary, doc.dump(2) + '\n');
        });
        writeSunJson(outputs, o->calibration, calibration.record, calibration.sun);
        outputs.commit();
        BackendOptions::storeBuiltKernels(executor);
        std::printf("wrote   %s%s%s\n", o->output.c_str(), wantCube ? " and " : "",
                    wantCube ? o->irradianceCube.c_str() : "");
        std::printf("time    ingest %.1f ms, sh %.1f ms, cube %.1f ms (%s), total %.1f ms\n", ingestMs, shMs,
                    cubeMs, executor.description().c_str(), millisecondsSince(start));
        return 0;
    };
}

} // namespace ibl::cli
