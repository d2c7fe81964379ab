#include "calibration_options.h"
#include "input_options.h"

#include <iblbake/error.h>
#include <iblbake/products.h>

#include <cstdio>
#include <fstream>

namespace ibl::cli {

void CalibrationOptions::addTo(CLI::App& command) {
    // The callbacks write into this object: it must outlive parsing at a fixed address (commands keep
    // their options in a shared_ptr).
    std::vector<CLI::Option*> sources = {
        command.add_option_function<double>(
            "--scale", [this](const double& v) { scale = v; },
            "calibration: multiply the input by K (manual factor)"),
        command.add_option_function<double>(
            "--ev100", [this](const double& v) { ev100 = v; },
            "calibration: the capture's EV100; L = value * 1.2 * 2^EV100 (Frostbite 5.1, Filament 8.1)"),
        command.add_option_function<double>(
            "--illuminance", [this](const double& v) { illuminance = v; },
            "calibration: illuminance in lux measured facing up (+Y) at the capture point"),
        command.add_option_function<double>(
            "--sun-illuminance", [this](const double& v) { sunIlluminance = v; },
            "calibration: the sun's illuminance in lux perpendicular to it (needs a detected sun)"),
        command.add_option_function<double>(
            "--sky-luminance", [this](const double& v) { skyLuminance = v; },
            "calibration: zenith sky luminance in cd/m2 (mean over 5 degrees around +Y, sun excluded)"),
        command.add_flag("--radiometric", radiometric,
                         "calibration: the input is radiance (W/sr/m2); multiply by 683 lm/W")};
    for (CLI::Option* a : sources) {
        a->group("Calibration source (one at most)");
        for (CLI::Option* b : sources)
            if (a != b) a->excludes(b);
    }
    CLI::Option* extract = command.add_flag("--extract-sun", extractSun,
                                            "take the detected sun out of the environment as a disk light");
    CLI::Option* json =
        command.add_option("--sun-json", sunJson, "where --extract-sun writes the sun's disk light (JSON)");
    CLI::Option* maxSolidAngle =
        command
            .add_option("--sun-max-solid-angle", sunMaxSolidAngle,
                        "largest bright core taken out as the disk (sr); above the default the detector "
                        "also takes a compact area light (a studio softbox: 7e-3 sr) as the disk")
            ->capture_default_str()
            ->check(CLI::Range(1e-6, 0.5));
    extract->needs(json);
    json->needs(extract);
    maxSolidAngle->needs(extract);
    for (CLI::Option* o : {extract, json, maxSolidAngle})
        o->group("Sun extraction");
}

bool CalibrationOptions::anySource() const {
    return scale || ev100 || illuminance || sunIlluminance || skyLuminance || radiometric;
}

CalibrationSettings CalibrationOptions::settings(const glm::dvec3& luminanceWeights) const {
    CalibrationSettings s;
    s.luminanceWeights = luminanceWeights;
    int count = 0;
    auto take = [&](const std::optional<double>& v, CalibrationSource source) {
        if (!v) return;
        ++count;
        s.source = source;
        s.value = *v;
    };
    take(scale, CalibrationSource::Scale);
    take(ev100, CalibrationSource::Ev100);
    take(illuminance, CalibrationSource::Illuminance);
    take(sunIlluminance, CalibrationSource::SunIlluminance);
    take(skyLuminance, CalibrationSource::SkyLuminance);
    if (radiometric) {
        ++count;
        s.source = CalibrationSource::Radiometric;
    }
    if (count > 1)
        throw Error(
            "give at most one calibration source (--scale, --ev100, --illuminance, --sun-illuminance, "
            "--sky-luminance, --radiometric)");
    return s;
}

CalibrationOutcome applyCalibration(const CalibrationOptions& options, SourceEnvironment& env,
                                    bool keepCubeWithSun) {
    const glm::dvec3 weights = workingLuminanceWeights(env.report.workingColorSpace);
    const CalibrationSettings settings = options.settings(weights);
    CalibrationOutcome out;
    try {
        out.record = computeCalibration(env.cube, settings);
        applyCalibration(env.cube, out.record.factor);
        if (options.extractSun) {
            SunDetectSettings sunSettings = settings.sun;
            sunSettings.luminanceWeights = weights;
            sunSettings.maxSolidAngle = options.sunMaxSolidAngle;
            const SunDetection sun = detectSun(env.cube, sunSettings);
            if (!sun.found) throw Error("--extract-sun: no sun detected: " + sun.reason);
            if (keepCubeWithSun) out.withSun = env.cube;
            out.sun = extractSun(env.cube, sun, weights);
        }
    } catch (const Error& e) {
        throw Error(env.report.file + ": " + e.what());
    }
    return out;
}

std::unique_ptr<AtomicFile> stageSunJson(const CalibrationOptions& options,
                                         const CalibrationOutcome& outcome) {
    if (options.sunJson.empty() || !outcome.sun) return nullptr;
    auto file = std::make_unique<AtomicFile>(options.sunJson);
    std::ofstream out(file->tempPath());
    out << sunJson(*outcome.sun, outcome.record) << "\n";
    out.close();
    if (!out) throw Error(options.sunJson + ": cannot write the sun's JSON");
    return file;
}

CalibratedInput ingestCalibrated(const InputOptions& input, const CalibrationOptions& calibration,
                                 int sourceFaceSize, bool keepCubeWithSun) {
    CalibratedInput out{ingestEnvironment(input.files(), input.settings(sourceFaceSize)), {}};
    out.calibration = applyCalibration(calibration, out.env, keepCubeWithSun);
    printIngestReport(out.env.report);
    const CalibrationOutcome& c = out.calibration;
    if (c.record.absolute()) std::printf("%s\n", c.record.summary().c_str());
    if (c.sun)
        std::printf("sun     extracted: %.6g lux at elevation %.2f deg, azimuth %.2f deg\n",
                    c.sun->illuminance, c.sun->elevationDegrees(), c.sun->azimuthDegrees());
    return out;
}

} // namespace ibl::cli
