// The flow of `iblbake calibrate` (docs/cli.md): an HDRI's calibrated environment in the input's own layout
// (environment.h calibrateInInputLayout) as a float OpenEXR, and the extracted sun as its light, by the
// products' writers (product_writers.h writeCalibratedEnvironment, writeSunProduct).
#pragma once

#include "iblbake/baker/environment.h"

#include <filesystem>
#include <string>

namespace ibl {

// Checks both files before any work, calibrates `input` with `settings` and writes `output` (and, when the
// sun was extracted and `sunJson` is not empty, its light), all of them or none. Errors:
// calibrateInInputLayout's (SettingError for a calibration or sun setting), then the writers'.
CalibratedImage calibrateToFiles(const std::filesystem::path& input, const EnvironmentSettings& settings,
                                 const std::filesystem::path& output, const std::filesystem::path& sunJson);

// What the command prints of it: the input, the calibration, the extracted sun, the file written.
std::string calibrateRunText(const CalibratedImage& calibrated, const std::filesystem::path& output,
                             const std::filesystem::path& sunJson);

} // namespace ibl
