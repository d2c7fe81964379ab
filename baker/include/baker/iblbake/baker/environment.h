// Environment preparation: the one sequence from HDR file(s) to what the bakes start from
// (docs/architecture.md "From HDRI to engine"): ingest (read, repair, colour conversion to the working space,
// source cube), calibration to absolute luminance (calibration.h: factor, then scaling), and the sun taken
// out as a disk light (sun.h). The CLI's baking commands and `iblbake calibrate`, a scene's environment, sun
// and probe stages and the accuracy sweep all prepare their environment here.
#pragma once

#include "iblbake/baker/calibration.h"
#include "iblbake/baker/environment_stats.h"
#include "iblbake/baker/ingest.h"
#include "iblbake/baker/sun.h"
#include "iblbake/core/cubemap.h"
#include "iblbake/core/image.h"

#include <filesystem>
#include <optional>
#include <vector>

namespace ibl {

enum class SunExtraction {
    Keep,       // the sun stays in the environment
    Required,   // taken out; an environment without a detected sun is an error
    IfDetected, // taken out when one is detected, else kept
};

struct EnvironmentSettings {
    IngestSettings ingest;
    // The factor's source and value. Its luminance weights (and those of its sun detection) are the working
    // colour space's (workingLuminanceWeights), whatever they hold here.
    CalibrationSettings calibration;
    SunExtraction sun = SunExtraction::Keep;
    // The largest core the extraction takes as the disk (SunDetectSettings::maxSolidAngle). The calibration's
    // own detection (sun-illuminance, sky-luminance) keeps calibration.sun's.
    double sunMaxSolidAngle = SunDetectSettings{}.maxSolidAngle;
    // Keep the calibrated cube from before the extraction (PreparedEnvironment::withSun): a specular
    // chain's level 0 keeps the sun's pixels (specular.h keepSunInLevel0).
    bool keepCubeWithSun = false;
};

struct PreparedEnvironment {
    SourceEnvironment env; // calibrated (env.cube scaled by record.factor), without the sun when taken out
    CalibrationRecord record;
    std::optional<DiskLight> sun;   // the light taken out of env.cube
    std::optional<CubeMap> withSun; // keepCubeWithSun and a sun taken out: env.cube before the extraction
};

// Errors: ingestEnvironment's, and after ingest, prefixed with the input file: SettingError "calibration"
// (computeCalibration's) and "extractSun" ("no sun detected: <reason>", SunExtraction::Required).
PreparedEnvironment prepareEnvironment(const std::vector<std::filesystem::path>& files,
                                       const EnvironmentSettings& settings);
// The same from an environment ingested already (settings.ingest is not used).
PreparedEnvironment prepareEnvironment(SourceEnvironment env, const EnvironmentSettings& settings);

// The extraction step alone, on calibrated texels: detectSun with `detection`, then extractSun with its
// luminance weights. Returns the light, or nothing (Keep; IfDetected without a sun). Throws SettingError
// "extractSun" ("no sun detected: <reason>") for Required without a sun. For callers that start from a
// calibrated grid: a scene's sun stage (its environment stage's cube), calibrateInInputLayout (lat-long
// pixels), the accuracy sweep (an ingested cube).
std::optional<DiskLight> takeSunOut(SphereTexels& texels, SunExtraction mode,
                                    const SunDetectSettings& detection);
std::optional<DiskLight> takeSunOut(CubeMap& cube, SunExtraction mode, const SunDetectSettings& detection);

// The calibrated environment in the input's own layout where that is lossless (what `iblbake calibrate`
// writes). The factor is always computed on the source cube, as prepareEnvironment does, so that both agree.
//   - lat-long input: the input's own pixels in the working space (readWorkingLatLong) times the factor,
//     nothing resampled; the sun is taken out of those pixels, with their exact solid angles, so the light
//     is exactly the energy taken out of the image. Its E_perp differs from the cube's (which the
//     sun-illuminance source calibrates) by the resampling: 0.1-0.7 % on the shared HDRIs.
//   - cube inputs: the prepared source cube as a vertical strip (faces +X, -X, +Y, -Y, +Z, -Z stacked,
//     OpenGL orientation, kernels/cube.h), which ingest reads back exactly.
// settings.keepCubeWithSun is not used. Errors: prepareEnvironment's.
struct CalibratedImage {
    ImageRGBA image;
    bool latLong = false; // else a vertical strip
    IngestReport report;  // of the ingest into the source cube
    CalibrationRecord record;
    std::optional<DiskLight> sun;
};
CalibratedImage calibrateInInputLayout(const std::filesystem::path& file,
                                       const EnvironmentSettings& settings);

} // namespace ibl
