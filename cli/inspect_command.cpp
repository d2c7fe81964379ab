// iblbake inspect: what an HDRI holds, photometrically (environment_stats.h, sun.h). Measured on the
// ingested source cube (exact per-texel solid angles), as every baking command sees the input.
//
// --json prints one JSON object (numbers that do not exist, e.g. EV100 of a black map, are null):
// {
//   "file": str, "width": int, "height": int,           // the input image
//   "layout": str, "faceSize": int,                     // detected layout; source cube face size
//   "latlongPixels": "centre" | "openexr",              // a lat-long's pixel placement (absent for cubes)
//   "inputColorSpace": str, "workingColorSpace": str,
//   "repaired": {"nan": int, "inf": int, "negative": int},  // channel values repaired on ingest
//   "units": "cd/m2" | "relative",                      // from the file's iblbake calibration metadata
//   "calibration": {attribute: str, ...} | null,        // that metadata ("iblbake:calibration.*", ...)
//   "luminance": {"min": num, "max": num,               // over the cube's texels
//                 "mean": num,                          // solid-angle-weighted over the sphere
//                 "logMean": num,                       // solid-angle-weighted geometric mean (Y > 0)
//                 "zenith": num},                       // mean over the 5-degree cap around +Y
//   "upwardIlluminance": num,                           // lux (if units are cd/m2): +Y hemisphere, cosine
//   "dynamicRange": {"stops": num,                      // log2(max / low)
//                    "low": num},                       // 0.1th percentile of Y > 0, by solid angle
//   "ev100": num | null,                                // log2(logMean * 100 / 12.5), Frostbite eq. 11
//   "ev100FromMean": num | null,                        // the same with the arithmetic mean
//   "sun": null | {"direction": [x, y, z],              // unit, +Y up, toward the sun
//                  "elevationDegrees": num, "azimuthDegrees": num,  // azimuth = atan2(x, z)
//                  "angularRadiusDegrees": num,         // equivalent disk (sun.h)
//                  "illuminance": num,                  // E_perp, lux (if units are cd/m2)
//                  "solidAngleSr": num,                 // of the measured region
//                  "color": [r, g, b],                  // luminance 1
//                  "contrast": num},                    // E_perp / (6.8e-5 sr * surroundings)
//   "sunInProbe": {"warning": str,                      // with a sun: one line (sun_in_probe.h)
//                  "roughness": [num], "keptError": [num], "extractedError": [num]},  // per column, 64 px
//   "noSunReason": str                                  // present when "sun" is null
// }
#include "commands.h"
#include "input_options.h"

#include <iblbake/baker/calibration.h>
#include <iblbake/baker/environment_stats.h>
#include <iblbake/baker/ingest.h>
#include <iblbake/baker/sun.h>
#include <iblbake/baker/sun_in_probe.h>
#include <iblbake/core/limits.h>

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <memory>

namespace ibl::cli {

namespace {

struct InspectOptions {
    std::string input;
    bool json = false;
    int size = 0;
    std::string layout = "auto";
    std::string inputColorSpace;
    std::string latLongPixels = "auto";
};

nlohmann::ordered_json numberOrNull(double v) {
    return std::isfinite(v) ? nlohmann::ordered_json(v) : nlohmann::ordered_json(nullptr);
}

} // namespace

Action addInspectCommand(CLI::App& app) {
    auto o = std::make_shared<InspectOptions>();
    CLI::App* cmd = app.add_subcommand(
        "inspect", "print an HDRI's luminance statistics, upward illuminance, suggested EV100 and sun");
    cmd->add_option("input", o->input, "HDR environment")->required();
    cmd->add_flag("--json", o->json, "print one JSON object (schema in cli/inspect_command.cpp)");
    cmd->add_option("--size", o->size, "face size of the source cube measured (default: from the input)")
        ->check(CLI::Range(0, limits::kMaxFaceSize));
    cmd->add_option("--layout", o->layout, "auto, latlong, exr-cube, hcross, vcross, hstrip, vstrip")
        ->capture_default_str();
    cmd->add_option("--input-colorspace", o->inputColorSpace,
                    "input colour space (default: file metadata, else lin_rec709; sRGB for 8-bit files)");
    addLatLongPixelsOption(*cmd, o->latLongPixels);

    return [o] {
        IngestSettings ingest;
        ingest.layout = parseLayout(o->layout);
        ingest.inputColorSpace = o->inputColorSpace;
        ingest.sourceFaceSize = o->size;
        ingest.latLongPixels = parseLatLongPixels(o->latLongPixels);
        const SourceEnvironment env = ingestEnvironment({o->input}, ingest);
        const IngestReport& r = env.report;
        const glm::dvec3 weights = workingLuminanceWeights(r.workingColorSpace);
        const SphereTexels texels(env.cube);
        const EnvironmentStats st = computeEnvironmentStats(texels, weights);
        const double zenith = zenithLuminance(texels, kZenithCapDegrees, weights);
        SunDetectSettings sunSettings;
        sunSettings.luminanceWeights = weights;
        const SunDetection sun = detectSun(texels, sunSettings);
        const auto calibration = readCalibrationMetadata(o->input);
        std::string units = "relative";
        for (const auto& [k, v] : calibration)
            if (k == "iblbake:units") units = v;
        const bool absolute = units == "cd/m2";
        // What a bake that keeps the detected sun, or a compact light the detector rejects by size, in the
        // probe costs at runtime (measured on a 64 px copy; without either, a detection only).
        const SunInProbe sunInProbe = measureSunInProbe(env.cube, Executor::cpu(), 5, sunSettings);

        if (o->json) {
            nlohmann::ordered_json j;
            j["file"] = r.file;
            j["width"] = r.width;
            j["height"] = r.height;
            j["layout"] = layoutName(r.layout);
            if (r.latLongPixels) j["latlongPixels"] = latLongPixelsName(*r.latLongPixels);
            j["faceSize"] = r.faceSize;
            j["inputColorSpace"] = r.inputColorSpace;
            j["workingColorSpace"] = r.workingColorSpace;
            j["repaired"] = {
                {"nan", r.nanRepaired}, {"inf", r.infRepaired}, {"negative", r.negativeRepaired}};
            j["units"] = units;
            if (calibration.empty()) {
                j["calibration"] = nullptr;
            } else {
                nlohmann::ordered_json c = nlohmann::ordered_json::object();
                for (const auto& [k, v] : calibration)
                    c[k] = v;
                j["calibration"] = c;
            }
            j["luminance"] = {{"min", st.minLuminance},
                              {"max", st.maxLuminance},
                              {"mean", st.meanLuminance},
                              {"logMean", st.logMeanLuminance},
                              {"zenith", zenith}};
            j["upwardIlluminance"] = st.upwardIlluminance;
            j["dynamicRange"] = {{"stops", st.dynamicRangeStops}, {"low", st.lowPercentileLuminance}};
            j["ev100"] = numberOrNull(st.ev100);
            j["ev100FromMean"] = numberOrNull(st.ev100FromMean);
            if (sun.found) {
                const DiskLight& l = sun.light;
                j["sun"] = {{"direction", {l.direction.x, l.direction.y, l.direction.z}},
                            {"elevationDegrees", l.elevationDegrees()},
                            {"azimuthDegrees", l.azimuthDegrees()},
                            {"angularRadiusDegrees", l.angularRadiusDegrees()},
                            {"illuminance", l.illuminance},
                            {"solidAngleSr", l.solidAngle},
                            {"color", {l.color.x, l.color.y, l.color.z}},
                            {"contrast", sun.contrast}};
                j["sunInProbe"] = {{"warning", sunInProbe.warning},
                                   {"roughness", sunInProbe.roughness},
                                   {"keptError", sunInProbe.keptError},
                                   {"extractedError", sunInProbe.extractedError}};
            } else {
                j["sun"] = nullptr;
                j["noSunReason"] = sun.reason;
                if (sunInProbe.compactLight)
                    j["compactLight"] = {{"angularRadiusDegrees", sunInProbe.angularRadiusDegrees},
                                         {"warning", sunInProbe.warning},
                                         {"roughness", sunInProbe.roughness},
                                         {"keptError", sunInProbe.keptError},
                                         {"extractedError", sunInProbe.extractedError}};
            }
            std::printf("%s\n", j.dump(2).c_str());
            return 0;
        }

        const char* lux = absolute ? "lux" : "lux-equivalent (relative units)";
        std::printf("input        %s: %dx%d %s, %s -> %s, source cube %d\n", r.file.c_str(), r.width,
                    r.height, layoutText(r).c_str(), r.inputColorSpace.c_str(), r.workingColorSpace.c_str(),
                    r.faceSize);
        std::printf("repaired     NaN %llu, Inf %llu, negative %llu channel values\n",
                    (unsigned long long)r.nanRepaired, (unsigned long long)r.infRepaired,
                    (unsigned long long)r.negativeRepaired);
        std::printf("units        %s\n", absolute ? "cd/m2 (iblbake calibration metadata)"
                                                  : "relative (no iblbake calibration metadata)");
        for (const auto& [k, v] : calibration)
            if (k != "iblbake:units") std::printf("  %-42s %s\n", k.c_str(), v.c_str());
        std::printf("luminance    min %.6g, max %.6g, mean %.6g (solid-angle weighted), log-mean %.6g, "
                    "zenith %.6g (5-degree cap)\n",
                    st.minLuminance, st.maxLuminance, st.meanLuminance, st.logMeanLuminance, zenith);
        std::printf("illuminance  %.6g %s upward (+Y hemisphere, cosine weighted)\n", st.upwardIlluminance,
                    lux);
        std::printf("dyn. range   %.2f stops (max / 0.1th percentile of positive luminance by solid angle, "
                    "%.4g)\n",
                    st.dynamicRangeStops, st.lowPercentileLuminance);
        std::printf("EV100        %.2f suggested (log-average luminance, K = 12.5); %.2f from the mean\n",
                    st.ev100, st.ev100FromMean);
        if (sun.found) {
            const DiskLight& l = sun.light;
            std::printf("sun          direction (%.4f, %.4f, %.4f), elevation %.2f deg, azimuth %.2f deg, "
                        "angular radius %.3f deg\n",
                        l.direction.x, l.direction.y, l.direction.z, l.elevationDegrees(), l.azimuthDegrees(),
                        l.angularRadiusDegrees());
            std::printf("             E_perp %.6g %s, solid angle %.4g sr, colour (%.3f, %.3f, %.3f), "
                        "contrast %.4g\n",
                        l.illuminance, lux, l.solidAngle, l.color.x, l.color.y, l.color.z, sun.contrast);
            std::printf("warning      %s\n", sunInProbe.warning.c_str());
        } else {
            std::printf("sun          no sun: %s\n", sun.reason.c_str());
            if (sunInProbe.compactLight) std::printf("warning      %s\n", sunInProbe.warning.c_str());
        }
        return 0;
    };
}

} // namespace ibl::cli
