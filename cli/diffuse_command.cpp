// iblbake diffuse: HDRI in, L2 SH (radiance and pre-scaled irradiance) out as JSON, optionally a small
// irradiance cube as KTX2.
#include "calibration_options.h"
#include "commands.h"
#include "common_options.h"
#include "input_options.h"

#include <iblbake/atomic_file.h>
#include <iblbake/error.h>
#include <iblbake/ingest.h>
#include <iblbake/irradiance.h>
#include <iblbake/ktx2.h>
#include <iblbake/sh.h>

#include <nlohmann/json.hpp>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <memory>
#include <optional>

namespace ibl::cli {

namespace {

constexpr int kSchemaVersion = 1;

// The calibration record as a JSON object (the same keys as the KTX2 key/value data, without prefix),
// with the extracted sun, if any, as a light object under "sunLight".
nlohmann::json calibrationJson(const CalibrationOutcome& calibration) {
    nlohmann::json out = nlohmann::json::object();
    for (const auto& [key, value] : calibration.metadata(""))
        out[key] = value;
    if (calibration.sun) out["sunLight"] = nlohmann::json::parse(diskLightToJson(*calibration.sun, true));
    return out;
}

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
    int size = 256;
    BackendOptions backend;
    CalibrationOptions calibration;
};

nlohmann::json rgb(const glm::dvec3& v) {
    return nlohmann::json::array({v.x, v.y, v.z});
}

nlohmann::json coefficients(const ShRgb& sh) {
    nlohmann::json a = nlohmann::json::array();
    for (const glm::dvec3& c : sh)
        a.push_back(rgb(c));
    return a;
}

const char* kIrradianceConvention =
    "pre-convolved with the clamped cosine (A_l = pi, 2pi/3, pi/4) and pre-scaled by the basis constants "
    "k_i: c_i = A_l k_i L_i. Filament's irradianceSH(n) = c0 + c1*n.y + c2*n.z + c3*n.x + c4*n.y*n.x + "
    "c5*n.y*n.z + c6*(3*n.z*n.z-1) + c7*n.z*n.x + c8*(n.x*n.x-n.y*n.y) returns the irradiance "
    "E(n) = integral L(l) max(0, n.l) dl (no 1/pi folded in); multiply by albedo/pi for Lambert radiance";
const char* kIrradianceOverPiConvention =
    "irradiance / pi (the Lambert 1/pi folded in, Filament cmgen's convention): irradianceSH(n) returns "
    "E(n)/pi, the cosine-weighted mean radiance, which is what the irradiance cube stores; multiply by "
    "albedo for Lambert radiance";
const char* kRadianceConvention =
    "L_i = integral L(w) Y_i(w) dw over every source texel (centre direction, exact solid angle, fp64 "
    "sums), standard orthonormal real SH; evaluate as sum L_i Y_i(w)";

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
        ->check(CLI::Range(1u, 1u << 20));
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
        if (o->size < 1 || o->size > 8192)
            throw Error("--size: " + std::to_string(o->size) + " is not from 1 to 8192");
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
        // Fail on unwritable outputs before the work; both files appear only when everything succeeded.
        AtomicFile jsonFile(o->output);
        std::optional<AtomicFile> cubeFile;
        if (wantCube) cubeFile.emplace(o->irradianceCube);

        Executor executor = o->backend.makeExecutor();
        CalibratedInput input = ingestCalibrated(o->input, o->calibration, o->size);
        const SourceEnvironment& env = input.env;
        const CalibrationOutcome& calibration = input.calibration;
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
            const std::string methodText =
                method == IrradianceMethod::Sampled
                    ? "sampled: cosine importance sampling, " +
                          std::to_string(irradianceSamplesFor(settings)) +
                          " samples/texel, pre-filtered lookups (Frostbite Listing 20 + Listing 19 LOD), "
                          "bright "
                          "texels integrated exactly"
                    : std::string(
                          "sh: the windowed L2 irradiance SH evaluated at each texel centre, negatives "
                          "clamped to 0");
            const char* normalization =
                "E/pi: each texel stores (1/pi) integral L(l) max(0,n.l) dl, the cosine-weighted mean "
                "radiance "
                "(Frostbite Listing 20's LD of a Lambert lobe); irradiance E = pi x value";
            Ktx2KeyValues kv = {{"iblbake.product", "irradiance"},
                                {"iblbake.irradianceNormalization", normalization},
                                {"iblbake.method", methodText},
                                {"iblbake.colorSpace", r.workingColorSpace},
                                {"iblbake.source", std::filesystem::path(r.file).filename().string()}};
            for (auto& entry : calibration.metadata("iblbake."))
                kv.push_back(entry);
            CubeMapChain chain;
            chain.levels.push_back(std::move(cube));
            Ktx2WriteStats stats = writeKtx2Cube(cubeFile->tempPath(), chain, format, kv);
            std::printf("cube    %d px %s, %s: %.1f ms, %llu clamped texels, %llu SH-negative texels\n",
                        o->irradianceSize, o->irradianceMethod.c_str(), o->format.c_str(), cubeMs,
                        (unsigned long long)stats.clampedTexels, (unsigned long long)shClamped);
            cubeJson = {{"file", o->irradianceCube},
                        {"faceSize", o->irradianceSize},
                        {"format", o->format},
                        {"method", irradianceMethodName(method)},
                        {"methodDetail", methodText},
                        {"normalization", normalization},
                        {"clampedTexels", stats.clampedTexels},
                        {"shNegativeTexels", shClamped}};
            if (method == IrradianceMethod::Sampled) cubeJson["samples"] = irradianceSamplesFor(settings);
            o->backend.printTiming(executor, "irradiance-cube", cubeMs);
        }

        nlohmann::json basis = nlohmann::json::array(
            {"(0,0) 0.282095", "(1,-1) 0.488603*y", "(1,0) 0.488603*z", "(1,1) 0.488603*x",
             "(2,-2) 1.092548*x*y", "(2,-1) 1.092548*y*z", "(2,0) 0.315392*(3*z*z-1)", "(2,1) 1.092548*x*z",
             "(2,2) 0.546274*(x*x-y*y)"});
        nlohmann::json doc = {
            {"schema", "iblbake.diffuse"},
            {"schemaVersion", kSchemaVersion},
            {"generator", "iblbake " IBLBAKE_VERSION},
            {"source",
             {{"file", r.file},
              {"width", r.width},
              {"height", r.height},
              {"layout", layoutName(r.layout)},
              {"inputColorSpace", r.inputColorSpace},
              {"faceSize", env.cube.faceSize},
              {"rotateDegrees", o->input.rotateDegrees}}},
            {"colorSpace", r.workingColorSpace},
            {"units", calibration.record.absolute() ? "cd/m2 (luminance); irradiance in lux"
                                                    : "relative (input values, uncalibrated)"},
            {"calibration", calibrationJson(calibration)},
            {"directions", "right-handed, +Y up; (x, y, z) of a unit direction as in DESIGN.md"},
            {"sh",
             {{"order", 2},
              {"coefficientCount", 9},
              {"basis", "real spherical harmonics, standard (orthonormal) normalization"},
              {"basisOrder", basis},
              {"clampedCosineFactors", {3.14159265358979323846, 2.0943951023931955, 0.78539816339744831}},
              {"window",
               {{"name", shWindowName(w.window)},
                {"parameter", w.parameter},
                {"parameterMeaning", w.window == ShWindow::Sloan ? "lambda: w_l = 1/(1+lambda l^2 (l+1)^2)"
                                     : w.window == ShWindow::Hanning
                                         ? "width w in bands: w_l = (1+cos(pi l/w))/2 for l < w, else 0"
                                     : w.window == ShWindow::Lanczos
                                         ? "width w in bands: w_l = sin(pi l/w)/(pi l/w) for l < w, else 0"
                                         : "no window"},
                {"requested", o->window},
                {"searched", w.searched},
                {"bandFactors", {w.factors[0], w.factors[1], w.factors[2]}},
                {"appliedTo", "radiance, irradiance and irradianceOverPi (not radianceUnwindowed)"}}},
              {"minIrradiance",
               {{"before", rgb(w.minBefore)},
                {"after", rgb(w.minAfter)},
                {"mean", rgb(w.meanIrradiance)},
                {"meaning", "minimum over the whole sphere of E(n) reconstructed from the SH, per channel, "
                            "without and with the window; mean = average of E over the sphere"}}},
              {"radianceUnwindowed", coefficients(sh.radianceRaw)},
              {"radiance", coefficients(sh.radiance)},
              {"radianceConvention", kRadianceConvention},
              {"irradiance", coefficients(sh.irradiance)},
              {"irradianceConvention", kIrradianceConvention},
              {"irradianceOverPi", coefficients(sh.irradianceOverPi)},
              {"irradianceOverPiConvention", kIrradianceOverPiConvention}}},
            {"timing", {{"ingestMs", ingestMs}, {"shMs", shMs}, {"irradianceCubeMs", cubeMs}}}};
        if (wantCube) doc["irradianceCube"] = cubeJson;

        {
            std::ofstream out(jsonFile.tempPath());
            out << doc.dump(2) << '\n';
            out.close();
            if (!out) throw Error(o->output + ": cannot write the JSON file");
        }
        auto sunJson = stageSunJson(o->calibration, calibration);
        if (cubeFile) cubeFile->commit();
        jsonFile.commit();
        if (sunJson) sunJson->commit();
        std::printf("wrote   %s%s%s\n", o->output.c_str(), wantCube ? " and " : "",
                    wantCube ? o->irradianceCube.c_str() : "");
        std::printf("time    ingest %.1f ms, sh %.1f ms, cube %.1f ms (%s), total %.1f ms\n", ingestMs, shMs,
                    cubeMs, executor.description().c_str(), millisecondsSince(start));
        return 0;
    };
}

} // namespace ibl::cli
