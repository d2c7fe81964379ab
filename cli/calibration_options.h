// Calibration options shared by the commands that read an HDRI (calibrate, specular, diffuse): one
// calibration source, and the optional sun extraction. The preparation itself is the library's
// (iblbake/baker/environment.h), and so are the plans that write the sun's light with --sun-json
// (iblbake/baker/product_plans.h); these turn the options into its settings and its errors into flag wording.
#pragma once

#include "common_options.h"

#include <iblbake/baker/calibration.h>
#include <iblbake/baker/environment.h>
#include <iblbake/baker/ingest.h>
#include <iblbake/baker/product_plans.h>
#include <iblbake/baker/sun.h>
#include <iblbake/core/error.h>

#include <CLI/CLI.hpp>

#include <chrono>
#include <functional>
#include <optional>
#include <string>

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
    CalibrationSettings settings() const;
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

// Runs a single-product command's plan (specular, diffuse) and prints it: the executor is made on its own
// thread while the input is read (`backend` nullopt: the plan needs none), a calibration error is named by
// its source's flag (withFlag); then the input's lines, --timing of `timedStage`, `productText` of the run
// and one time line (the ingest, each product stage, the total since `start`).
int runProductCommand(const ProductPlan& plan, const CalibrationOptions& calibration,
                      const BackendOptions& backendOptions, std::optional<Backend> backend,
                      const std::string& timedStage,
                      const std::function<std::string(const ProductRun&)>& productText,
                      std::chrono::steady_clock::time_point start);

} // namespace ibl::cli
