// Calibration options shared by the commands that read an HDRI (calibrate, specular, diffuse): one
// calibration source, and the optional sun extraction. The preparation itself is the library's
// (iblbake/baker/environment.h), and so are the plans that write the sun's light with --sun-json
// (iblbake/baker/product_plans.h); these turn the options into its settings and its errors into flag wording.
#pragma once

#include <iblbake/baker/calibration.h>
#include <iblbake/baker/environment.h>
#include <iblbake/baker/ingest.h>
#include <iblbake/baker/product_plans.h>
#include <iblbake/baker/sun.h>
#include <iblbake/core/error.h>

#include <CLI/CLI.hpp>

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace ibl::cli {

struct CalibrationOptions {
    std::optional<double> scale, ev100, illuminance, sunIlluminance, skyLuminance;
    bool radiometric = false;
    bool extractSun = false;
    std::string sunJson;
    double sunMaxSolidAngle = SunDetectSettings{}.maxSolidAngle;

    // --scale, --ev100, --illuminance, --sun-illuminance, --sky-luminance, --radiometric (at most one: a
    // second is a one-line parse error), --extract-sun and --sun-json (each needs the other),
    // --sun-max-solid-angle.
    void addTo(CLI::App& command);
    bool anySource() const;
    CalibrationSettings settings() const; // throws ibl::Error on > 1 source
    // The library's settings: `ingest` and these options.
    EnvironmentSettings environmentSettings(const IngestSettings& ingest) const;
};

// A library error about one setting with the flag that set it in front, e.g. "--sun-illuminance:
// park.hdr: no sun detected: ..." (`calibration`: the chosen source's flag).
Error withFlag(const SettingError& error, const CalibrationOptions& calibration);

struct InputOptions;

// The environment a baking command reads (product_plans.h EnvironmentJob), at `sourceFaceSize`.
EnvironmentJob environmentJob(const InputOptions& input, const CalibrationOptions& calibration,
                              int sourceFaceSize);

// runProductPlan, a calibration error named by its source's flag (withFlag).
ProductRun runCalibrated(const ProductPlan& plan, const CalibrationOptions& calibration,
                         const std::function<const Executor*()>& executor);

} // namespace ibl::cli
