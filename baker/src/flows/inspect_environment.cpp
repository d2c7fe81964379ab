// `iblbake inspect`'s measurements and document (iblbake/baker/inspect.h).
#include "iblbake/baker/inspect.h"

#include "iblbake/baker/calibration.h"
#include "iblbake/core/format_text.h"
#include "iblbake/opencl/executor.h"

#include <cmath>

namespace ibl {

namespace {

nlohmann::ordered_json numberOrNull(double v) {
    return std::isfinite(v) ? nlohmann::ordered_json(v) : nlohmann::ordered_json(nullptr);
}

} // namespace

EnvironmentInspection inspectEnvironment(const std::filesystem::path& file, const IngestSettings& ingest) {
    const SourceEnvironment env = ingestEnvironment({file}, ingest);
    EnvironmentInspection inspection;
    inspection.report = env.report;
    const glm::dvec3 weights = workingLuminanceWeights(env.report.workingColorSpace);
    const SphereTexels texels(env.cube);
    inspection.stats = computeEnvironmentStats(texels, weights);
    inspection.zenithLuminance = zenithLuminance(texels, kZenithCapDegrees, weights);
    SunDetectSettings sunSettings;
    sunSettings.luminanceWeights = weights;
    inspection.sun = detectSun(texels, sunSettings);
    inspection.calibration = readCalibrationMetadata(file);
    for (const auto& [key, value] : inspection.calibration)
        if (key == "iblbake:units") inspection.units = value;
    inspection.sunInProbe = measureSunInProbe(env.cube, Executor::cpu(), 5, sunSettings);
    return inspection;
}

std::string layoutText(const IngestReport& r) {
    std::string text = layoutName(r.layout);
    if (r.latLongPixels) text += std::string(" (pixels ") + latLongPixelsName(*r.latLongPixels) + ")";
    return text;
}

std::string ingestReportText(const IngestReport& r) {
    return formatText("input   %s: %dx%d %s, %s -> %s, max luminance %.6g\n", r.file.c_str(), r.width,
                      r.height, layoutText(r).c_str(), r.inputColorSpace.c_str(), r.workingColorSpace.c_str(),
                      r.maxLuminanceIn) +
           formatText("repaired NaN %llu, Inf %llu, negative %llu channel values\n",
                      (unsigned long long)r.nanRepaired, (unsigned long long)r.infRepaired,
                      (unsigned long long)r.negativeRepaired);
}

std::string preparationText(const CalibrationRecord& record, const std::optional<DiskLight>& sun) {
    std::string text = record.absolute() ? record.summary() + "\n" : "";
    if (sun)
        text += formatText("sun     extracted: %.6g lux at elevation %.2f deg, azimuth %.2f deg\n",
                           sun->illuminance, sun->elevationDegrees(), sun->azimuthDegrees());
    return text;
}

std::string inspectionText(const EnvironmentInspection& inspection) {
    std::string text;
    const auto line = [&](const char* pattern, auto... values) { text += formatText(pattern, values...); };
    const IngestReport& r = inspection.report;
    const EnvironmentStats& st = inspection.stats;
    const SunDetection& sun = inspection.sun;
    const bool absolute = inspection.absolute();
    const char* lux = absolute ? "lux" : "lux-equivalent (relative units)";
    line("input        %s: %dx%d %s, %s -> %s, source cube %d\n", r.file.c_str(), r.width, r.height,
         layoutText(r).c_str(), r.inputColorSpace.c_str(), r.workingColorSpace.c_str(), r.faceSize);
    line("repaired     NaN %llu, Inf %llu, negative %llu channel values\n", (unsigned long long)r.nanRepaired,
         (unsigned long long)r.infRepaired, (unsigned long long)r.negativeRepaired);
    line("units        %s\n",
         absolute ? "cd/m2 (iblbake calibration metadata)" : "relative (no iblbake calibration metadata)");
    for (const auto& [k, v] : inspection.calibration)
        if (k != "iblbake:units") line("  %-42s %s\n", k.c_str(), v.c_str());
    line("luminance    min %.6g, max %.6g, mean %.6g (solid-angle weighted), log-mean %.6g, "
         "zenith %.6g (5-degree cap)\n",
         st.minLuminance, st.maxLuminance, st.meanLuminance, st.logMeanLuminance, inspection.zenithLuminance);
    line("illuminance  %.6g %s upward (+Y hemisphere, cosine weighted)\n", st.upwardIlluminance, lux);
    line("dyn. range   %.2f stops (max / 0.1th percentile of positive luminance by solid angle, "
         "%.4g)\n",
         st.dynamicRangeStops, st.lowPercentileLuminance);
    line("EV100        %.2f suggested (log-average luminance, K = 12.5); %.2f from the mean\n", st.ev100,
         st.ev100FromMean);
    if (sun.found) {
        const DiskLight& l = sun.light;
        line("sun          direction (%.4f, %.4f, %.4f), elevation %.2f deg, azimuth %.2f deg, "
             "angular radius %.3f deg\n",
             l.direction.x, l.direction.y, l.direction.z, l.elevationDegrees(), l.azimuthDegrees(),
             l.angularRadiusDegrees());
        line("             E_perp %.6g %s, solid angle %.4g sr, colour (%.3f, %.3f, %.3f), "
             "contrast %.4g\n",
             l.illuminance, lux, l.solidAngle, l.color.x, l.color.y, l.color.z, sun.contrast);
        line("warning      %s\n", inspection.sunInProbe.warning.c_str());
    } else {
        line("sun          no sun: %s\n", sun.reason.c_str());
        if (inspection.sunInProbe.compactLight)
            line("warning      %s\n", inspection.sunInProbe.warning.c_str());
    }
    return text;
}

nlohmann::ordered_json inspectionJson(const EnvironmentInspection& inspection) {
    const IngestReport& r = inspection.report;
    const EnvironmentStats& st = inspection.stats;
    const SunDetection& sun = inspection.sun;
    const SunInProbe& sunInProbe = inspection.sunInProbe;
    nlohmann::ordered_json j;
    j["file"] = r.file;
    j["width"] = r.width;
    j["height"] = r.height;
    j["layout"] = layoutName(r.layout);
    if (r.latLongPixels) j["latlongPixels"] = latLongPixelsName(*r.latLongPixels);
    j["faceSize"] = r.faceSize;
    j["inputColorSpace"] = r.inputColorSpace;
    j["workingColorSpace"] = r.workingColorSpace;
    j["repaired"] = {{"nan", r.nanRepaired}, {"inf", r.infRepaired}, {"negative", r.negativeRepaired}};
    j["units"] = inspection.units;
    if (inspection.calibration.empty()) {
        j["calibration"] = nullptr;
    } else {
        nlohmann::ordered_json c = nlohmann::ordered_json::object();
        for (const auto& [k, v] : inspection.calibration)
            c[k] = v;
        j["calibration"] = c;
    }
    j["luminance"] = {{"min", st.minLuminance},
                      {"max", st.maxLuminance},
                      {"mean", st.meanLuminance},
                      {"logMean", st.logMeanLuminance},
                      {"zenith", inspection.zenithLuminance}};
    j["upwardIlluminance"] = st.upwardIlluminance;
    j["dynamicRange"] = {{"stops", st.dynamicRangeStops}, {"low", st.lowPercentileLuminance}};
    j["ev100"] = numberOrNull(st.ev100);
    j["ev100FromMean"] = numberOrNull(st.ev100FromMean);
    const nlohmann::ordered_json probeCost = {{"warning", sunInProbe.warning},
                                              {"roughness", sunInProbe.roughness},
                                              {"keptError", sunInProbe.keptError},
                                              {"extractedError", sunInProbe.extractedError}};
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
        j["sunInProbe"] = probeCost;
    } else {
        j["sun"] = nullptr;
        j["noSunReason"] = sun.reason;
        if (sunInProbe.compactLight) {
            nlohmann::ordered_json compact = {{"angularRadiusDegrees", sunInProbe.angularRadiusDegrees}};
            compact.update(probeCost);
            j["compactLight"] = compact;
        }
    }
    return j;
}

} // namespace ibl
