// Calibration options shared by the commands that read an HDRI (calibrate; specular and diffuse can add
// them the same way): one calibration source, and the optional sun extraction.
//
//   CalibrationOptions calibration;          // in the command's option struct
//   calibration.addTo(*cmd);                 // when building the subcommand
//   ...
//   SourceEnvironment env = ingestEnvironment(files, ingest);
//   CalibrationOutcome cal = applyCalibration(calibration, env);  // scales env.cube, extracts the sun
//   keyValues = ldChainKeyValues(..., cal.record, cal.sun);  // products.h builds the output's metadata
//   auto sunJson = stageSunJson(calibration, cal);  // before writing the main output ...
//   ... write the main output ...
//   if (sunJson) sunJson->commit();                 // ... and committed after it
#pragma once

#include <iblbake/atomic_file.h>
#include <iblbake/calibration.h>
#include <iblbake/ingest.h>
#include <iblbake/sun.h>

#include <CLI/CLI.hpp>

#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace ibl::cli {

struct CalibrationOutcome {
    CalibrationRecord record;
    std::optional<DiskLight> sun;   // the extracted sun (with --extract-sun)
    std::optional<CubeMap> withSun; // the calibrated cube before the extraction (keepCubeWithSun)
};

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
    CalibrationSettings settings(const glm::dvec3& luminanceWeights) const; // throws ibl::Error on > 1 source
};

// Computes the factor on env.cube (environment_stats.h / calibration.h), scales every texel by it, and
// with --extract-sun takes the sun out of the scaled cube. Throws ibl::Error "<input>: --option: ..."
// when the source cannot be used (e.g. --sun-illuminance on a map without a sun). With keepCubeWithSun,
// the outcome also holds the calibrated cube before the extraction (the specular chain's level 0).
CalibrationOutcome applyCalibration(const CalibrationOptions& options, SourceEnvironment& env,
                                    bool keepCubeWithSun = false);

// With --sun-json: the light written to a temporary file beside the target; commit() it once the main
// output is written, so that a failed run leaves neither. nullptr without --sun-json.
std::unique_ptr<AtomicFile> stageSunJson(const CalibrationOptions& options,
                                         const CalibrationOutcome& outcome);

struct InputOptions;

// What a baking command starts from: the ingested environment, calibrated (and with the sun taken out
// when asked).
struct CalibratedInput {
    SourceEnvironment env;
    CalibrationOutcome calibration;
};

// Ingests the input at `sourceFaceSize`, applies the calibration, and prints the input report, the
// calibration and the extracted sun. keepCubeWithSun: as applyCalibration's.
CalibratedInput ingestCalibrated(const InputOptions& input, const CalibrationOptions& calibration,
                                 int sourceFaceSize, bool keepCubeWithSun = false);

} // namespace ibl::cli
