// `iblbake inspect`'s flow: what an HDRI holds, photometrically (environment_stats.h, sun.h), measured on
// the ingested source cube (exact per-texel solid angles), as every baking command sees the input.
//
// inspectionJson is one JSON object (numbers that do not exist, e.g. EV100 of a black map, are null):
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
#pragma once

#include "iblbake/baker/calibration.h"
#include "iblbake/baker/environment_stats.h"
#include "iblbake/baker/ingest.h"
#include "iblbake/baker/sun.h"
#include "iblbake/baker/sun_in_probe.h"

#include <nlohmann/json.hpp>

#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace ibl {

struct EnvironmentInspection {
    IngestReport report;
    std::vector<std::pair<std::string, std::string>> calibration; // the file's iblbake calibration metadata
    std::string units = "relative";                               // "cd/m2" when that metadata says so
    EnvironmentStats stats;
    double zenithLuminance = 0.0; // mean over the kZenithCapDegrees cap around +Y
    SunDetection sun;
    // What a bake that keeps the detected sun, or a compact light the detector rejects by size, in the probe
    // costs at runtime (measured on a 64 px copy; without either, a detection only).
    SunInProbe sunInProbe;
    bool absolute() const { return units == "cd/m2"; }
};

// Ingests `file` with `ingest` and measures it (on the CPU). Throws ingest's errors.
EnvironmentInspection inspectEnvironment(const std::filesystem::path& file, const IngestSettings& ingest);

// The document above.
nlohmann::ordered_json inspectionJson(const EnvironmentInspection& inspection);
// The same for people (`iblbake inspect`): the input, units, luminance, illuminance, dynamic range, EV100 and
// the sun, one line each.
std::string inspectionText(const EnvironmentInspection& inspection);

// The input's layout as the commands print it: "latlong (pixels centre)", "exr-cube".
std::string layoutText(const IngestReport& report);

// The baking commands' report of their input: the "input" line (file, size, layout, colour spaces, brightest
// luminance) and the "repaired" line; and of its preparation: the calibration (when absolute) and the sun
// taken out, one line each.
std::string ingestReportText(const IngestReport& report);
std::string preparationText(const CalibrationRecord& record, const std::optional<DiskLight>& sun);

} // namespace ibl
