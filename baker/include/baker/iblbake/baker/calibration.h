// Calibration to absolute luminance (docs/conventions.md "Units and calibration": after calibration, pixel
// values are luminance in cd/m2; the factor and its source are recorded). Captures usually hold relative
// luminance (Frostbite 4.9.1); one multiplier, found from one known quantity, makes them absolute.
//
// Sources (exactly one):
//   scale K          factor = K.
//   ev100 EV         the EV100 the capture was exposed at. Camera model of Frostbite 5.1 (Listing 28,
//                    convertEV100ToExposure) and Filament 8.1.3 (exposure()): a pixel holds the
//                    luminance normalized by the luminance that saturates the sensor at ISO 100,
//                    value = L * exposure, exposure = 1 / Lmax, Lmax = 78 / (S q) * N^2 / t
//                    = 78 / (100 * 0.65) * 2^EV100 = 1.2 * 2^EV100 (eq. 75, with N^2 / t = 2^EV100 at
//                    S = 100 and lens attenuation q = 0.65). Hence L = value * 1.2 * 2^EV100:
//                    factor = 1.2 * 2^EV100.
//   illuminance LUX  measured with an incident light meter facing up (+Y) at the capture point:
//                    factor = LUX / E_up, E_up the map's upward illuminance (environment_stats.h).
//   sun-illuminance LUX  the sun's illuminance on a surface perpendicular to it (Frostbite 4.6 E_perp,
//                    Table 11 "Sun perp", e.g. 100 000 - 120 000 lux at midday): factor = LUX / E_perp of
//                    the detected sun (sun.h). Throws when no sun is detected.
//   sky-luminance NITS  the ZENITH luminance (a spot meter pointed straight up; Frostbite 4.9.1 gives
//                    ~8000 cd/m2 for a clear sky, ~2000 overcast): factor = NITS / L_zenith, L_zenith the
//                    solid-angle mean over the 5-degree cap around +Y, the detected sun's texels excluded.
//                    Zenith rather than a hemisphere mean because it is what one reading measures and is
//                    sky in almost every outdoor capture, where a hemisphere mean mixes in buildings and
//                    trees.
//   radiometric      the values are radiance (W sr^-1 m^-2, as Maxwell and V-Ray treat HDRIs, Frostbite
//                    footnote 37): factor = 683 lm/W (eq. 10, eta = 683 for every wavelength).
//   none             factor = 1, units stay relative.
#pragma once

#include "iblbake/baker/environment_stats.h"
#include "iblbake/baker/ingest.h"
#include "iblbake/baker/sun.h"
#include "iblbake/core/cubemap.h"
#include "iblbake/core/image.h"

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace ibl {

enum class CalibrationSource { None, Scale, Ev100, Illuminance, SunIlluminance, SkyLuminance, Radiometric };

// The option-style name: none, scale, ev100, illuminance, sun-illuminance, sky-luminance, radiometric.
const char* calibrationSourceName(CalibrationSource source);

inline constexpr double kLuminousEfficacy = 683.0; // lm/W (Frostbite eq. 10, footnote 37)
inline constexpr double kZenithCapDegrees = 5.0;

struct CalibrationSettings {
    CalibrationSource source = CalibrationSource::None;
    double value = 0.0; // K, EV100, lux, lux, cd/m2; unused for None and Radiometric
    glm::dvec3 luminanceWeights = kRec709Luminance;
    SunDetectSettings sun; // for SunIlluminance and SkyLuminance (its luminanceWeights are overridden)
};

struct CalibrationRecord {
    double factor = 1.0;
    CalibrationSource source = CalibrationSource::None;
    double sourceValue = 0.0; // the user's number (K, EV100, lux, cd/m2)
    // The quantity the source pins down, before and after (after = factor * before: every quantity is
    // linear in the pixels). For scale, ev100, radiometric and none: the mean luminance.
    std::string quantity; // e.g. "upward illuminance (lux)"
    double measuredBefore = 0.0, measuredAfter = 0.0;
    // Always measured, for the record.
    double upwardIlluminanceBefore = 0.0, upwardIlluminanceAfter = 0.0;
    double meanLuminanceBefore = 0.0, meanLuminanceAfter = 0.0;
    bool sunMeasured = false; // sun quantities below are valid (sun-illuminance, sky-luminance sources)
    bool sunFound = false;
    double sunIlluminanceBefore = 0.0, sunIlluminanceAfter = 0.0;

    bool absolute() const { return source != CalibrationSource::None; } // values are cd/m2 afterwards
    std::string units() const { return absolute() ? "cd/m2" : "relative"; }
    std::string summary() const; // one line for the console
};

// Measures `texels` and computes the factor. Throws ibl::SettingError with setting() "calibration" (the
// message says what is wrong, e.g. "no sun detected: ...", the caller names its source: a flag, a scene
// key) when the value is not usable (not finite, not positive where it must be) or the measured quantity is
// zero or absent.
CalibrationRecord computeCalibration(const SphereTexels& texels, const CalibrationSettings& settings);
CalibrationRecord computeCalibration(const CubeMap& cube, const CalibrationSettings& settings);

// Multiplies R, G, B of every texel by `factor` (alpha untouched).
void applyCalibration(CubeMap& cube, double factor);
void applyCalibration(ImageRGBA& image, double factor);

// Metadata for an output: keys prefix + "calibration.factor", ".source", ".sourceValue", ".quantity",
// ".measuredBefore", ".measuredAfter", ".upwardIlluminanceBefore/After", ".meanLuminanceBefore/After",
// ".sunIlluminanceBefore/After" (when measured), and prefix + "units". Numbers with 9 significant digits.
// Prefix "iblbake:" for OpenEXR attributes, "iblbake." for KTX2 key/values.
std::vector<std::pair<std::string, std::string>> calibrationMetadata(const CalibrationRecord& record,
                                                                     const std::string& prefix);

// The "iblbake:calibration.*", "iblbake:units" and "iblbake:sun*" attributes of an image file (what
// `iblbake calibrate` writes), in file order; empty when there are none or the file cannot be read.
std::vector<std::pair<std::string, std::string>> readCalibrationMetadata(const std::filesystem::path& file);

// The luminance weights of a working colour space: kRec709Luminance (0.2126, 0.7152, 0.0722) for
// lin_rec709; for others (acescg) the Y row of their RGB -> XYZ matrix via the OCIO config. Throws
// ibl::Error for a space the config does not know.
glm::dvec3 workingLuminanceWeights(const std::string& workingColorSpace);

// The same read -> repair -> colour conversion -> repair as ingestEnvironment, without resampling into a
// cube: the input lat-long in the working space at its own resolution, for outputs that keep the input's
// layout (`iblbake calibrate`). settings.layout must resolve to LatLong and rotation must be 0 (throws
// ibl::Error naming the file otherwise). `report` gets what ingestEnvironment would report, faceSize 0 (its
// latLongPixels is the placement the pixels are to be read with, SphereTexels(image, placement)).
ImageRGBA readWorkingLatLong(const std::filesystem::path& file, const IngestSettings& settings,
                             IngestReport* report = nullptr);

} // namespace ibl
