#include "calibration_options.h"
#include "input_options.h"
#include "setting_flags.h"

#include <iblbake/core/error.h>
#include <iblbake/core/limits.h>

#include <cstdio>

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
            ->check(CLI::Range(limits::kMinSunMaxSolidAngle, limits::kMaxSunMaxSolidAngle));
    extract->needs(json);
    json->needs(extract);
    maxSolidAngle->needs(extract);
    for (CLI::Option* o : {extract, json, maxSolidAngle})
        o->group("Sun extraction");
}

bool CalibrationOptions::anySource() const {
    return scale || ev100 || illuminance || sunIlluminance || skyLuminance || radiometric;
}

CalibrationSettings CalibrationOptions::settings() const {
    CalibrationSettings s; // at most one source: the flags exclude each other (addTo)
    const auto take = [&](const std::optional<double>& v, CalibrationSource source) {
        if (v) {
            s.source = source;
            s.value = *v;
        }
    };
    take(scale, CalibrationSource::Scale);
    take(ev100, CalibrationSource::Ev100);
    take(illuminance, CalibrationSource::Illuminance);
    take(sunIlluminance, CalibrationSource::SunIlluminance);
    take(skyLuminance, CalibrationSource::SkyLuminance);
    if (radiometric) s.source = CalibrationSource::Radiometric;
    return s;
}

EnvironmentSettings CalibrationOptions::environmentSettings(const IngestSettings& ingest) const {
    EnvironmentSettings s;
    s.ingest = ingest;
    s.calibration = settings();
    s.sun = extractSun ? SunExtraction::Required : SunExtraction::Keep;
    s.sunMaxSolidAngle = sunMaxSolidAngle;
    return s;
}

Error withFlag(const SettingError& error, const CalibrationOptions& calibration) {
    if (error.setting() != "calibration") return Error(flaggedMessage(error));
    // The source's own flag: --scale, --ev100, --illuminance, --sun-illuminance, --sky-luminance.
    return Error(std::string("--") + calibrationSourceName(calibration.settings().source) + ": " +
                 error.what());
}

EnvironmentJob environmentJob(const InputOptions& input, const CalibrationOptions& calibration,
                              int sourceFaceSize) {
    EnvironmentJob job;
    job.files = input.files();
    job.layout = input.layout;
    job.inputColorSpace = input.inputColorSpace;
    job.workingColorSpace = input.workingColorSpace;
    job.rotateDegrees = input.rotateDegrees;
    job.latLongPixels = input.latLongPixels;
    job.calibration = calibration.settings();
    job.faceSize = sourceFaceSize;
    job.extractSun = calibration.extractSun;
    job.sunMaxSolidAngle = calibration.sunMaxSolidAngle;
    job.sunJson = calibration.sunJson;
    return job;
}

int runProductCommand(const ProductPlan& plan, const CalibrationOptions& calibration,
                      const BackendOptions& backendOptions, std::optional<Backend> backend,
                      const std::string& timedStage,
                      const std::function<std::string(const ProductRun&)>& productText,
                      std::chrono::steady_clock::time_point start) {
    std::future<Executor> pendingExecutor;
    if (backend) pendingExecutor = backendOptions.startExecutor(*backend);
    std::optional<Executor> executor;
    ProductRun run;
    try {
        run = runProductPlan(plan, [&] { return &executor.emplace(pendingExecutor.get()); });
    } catch (const SettingError& e) {
        throw withFlag(e, calibration);
    }
    std::printf("%s", environmentRunText(run).c_str());
    if (executor) {
        backendOptions.printTiming(*executor, timedStage.c_str(), 1000.0 * run.stageSeconds(timedStage));
        BackendOptions::storeBuiltKernels(*executor);
    }
    std::printf("%s", productText(run).c_str());
    std::printf("time    ingest %.1f ms",
                1000.0 * (run.stageSeconds("environment") + run.stageSeconds("sun")));
    for (const StageResult& stage : run.stages)
        if (stage.id != "environment" && stage.id != "sun")
            std::printf(", %s %.1f ms", stage.id.c_str(), 1000.0 * stage.seconds);
    std::printf(", total %.1f ms (%s)\n", millisecondsSince(start),
                executor ? executor->description().c_str() : "cpu");
    return 0;
}

} // namespace ibl::cli
