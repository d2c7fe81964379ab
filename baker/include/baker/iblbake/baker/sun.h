// The sun in an HDRI: detection, measurement, and extraction into an analytic disk light (Frostbite 4.6,
// Listing 6; removal as in 4.9.1: "copy and paste a small part of the surrounding sky onto the sun").
//
// Detection (sun_detect.cpp), on any SphereTexels grid (source cube or lat-long pixels); luminance Y as in
// environment_stats.h:
//   1. Sky level S: the solid-angle-weighted median Y of the upper hemisphere (robust: the sun, however
//      bright, is a tiny share of its solid angle).
//   2. Candidate: the brightest texel (peak). Surroundings level B: the solid-angle-weighted median Y of
//      the ring 2 to 6 degrees from it (the sky right around the sun; outside the blurred disk of any
//      capture we have seen, inside the "surroundings" a photographer would meter).
//   3. Threshold T = max(16 B, sqrt(peak * B)): at least 4 stops over the surroundings, and half way (in
//      stops) from them to the peak, so the disk is taken and the aureole mostly left in the sky.
//      Core = texels above T 8-connected to the peak; region = core plus a one-texel margin. The margin takes
//      in the spill of a disk blurred by the capture or by the lat-long -> cube resampling (measured: it
//      makes E_perp agree between a 1k lat-long and its 256 cube within 0.2 % on the three sun maps, against
//      4 % without), and leaves every texel just outside the region at or below T.
//   4. Background inside the region: the harmonic (membrane) fill from its outer boundary, per channel:
//      smooth, and a convex combination of boundary values, so <= T in luminance.
//   5. E_perp = luminance of sum over the region of max(L - fill, 0) * omega (per channel), in lux: the
//      disk subtends < 1 degree, so cos ~ 1 over it (Frostbite footnote 29: lux = luminance * solid
//      angle). Direction, radius, colour: diskLightFromExcess.
//   It is a sun when: the peak is above T (else: not even 4 stops over its surroundings); the core's solid
//   angle is at most maxSolidAngle (compact; not an area light); the core holds more than minEnergyShare
//   of the light above T on the whole sphere (one dominant source, not one of several); and the contrast
//   E_perp / (kSunSolidAngle * max(B, S)) -- the light's luminance were it a sun-sized disk, over its
//   surroundings -- is at least minContrast. Measured with energy, the contrast does not depend on the
//   grid's resolution, where a peak texel's does (venice_sunset: 93 at face size 64, 867 at 512).
//   Otherwise: no sun, and the reason.
//
// Extraction (sun_extract.cpp) writes min(fill, L) per channel into the region (never negative, never
// brighter), and the light's E_perp is by definition the energy removed: sum over the region of
// (L_before - L_after) * omega, computed from the stored floats, so light + residual == input.
#pragma once

#include "iblbake/baker/environment_stats.h"

#include <cstddef>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

namespace ibl {

// A distant disk light (Frostbite 4.6): what the renderer adds back for the extracted sun.
struct DiskLight {
    glm::dvec3 direction{0.0, 1.0, 0.0}; // unit, toward the light, docs/conventions.md frame (+Y up)
    // Radians: the disk equivalent to the measured energy (diskLightFromExcess). Capture blur and the
    // texel size inflate it: 0.4-0.5 degrees on the 1k maps, where the sun's is 0.27 (footnote 28); a
    // renderer wanting the true sun can override it without changing E_perp.
    double angularRadius = 0.0;
    // Normalized linear colour in the working space: its luminance is 1, so illuminance * color is the
    // RGB illuminance the light delivers on a surface facing it.
    glm::dvec3 color{1.0};
    double illuminance = 0.0; // E_perp, lux (relative units before calibration), perpendicular to it
    double solidAngle = 0.0;  // steradians of the texel region it was measured over (not of the disk)

    double elevationDegrees() const; // asin(direction.y)
    // Longitude of the docs/conventions.md lat-long mapping: atan2(x, z), 0 at +Z, +90 at +X; the lat-long
    // pixel column is u = 0.5 - azimuth / 360.
    double azimuthDegrees() const;
    double angularRadiusDegrees() const;
    double diskSolidAngle() const; // 2 pi (1 - cos angularRadius)
};

// JSON (document schema, all numbers finite):
// { "type": "disk", "direction": [x, y, z], "elevationDegrees": e, "azimuthDegrees": a,
//   "angularRadiusDegrees": r, "color": [r, g, b], "illuminanceLux": E, "solidAngleSr": omega,
//   "units": "lux" | "relative" }
// diskLightFromJson reads what diskLightToJson writes (elevation/azimuth are derived, ignored on read);
// throws ibl::Error naming the first missing or malformed field.
std::string diskLightToJson(const DiskLight& light, bool calibrated, int indent = 2);
DiskLight diskLightFromJson(const std::string& json);

inline constexpr double kSunSolidAngle = 6.8e-5; // sr, the sun seen from Earth (Frostbite footnote 28)

// Defaults chosen on the shared HDRIs (SOURCES.md), measured on their 256 source cubes and 1k lat-longs:
// contrast 900-13000 for the four sunny maps; core 2.3e-4 to 3.7e-4 sr for the three clean suns, 2e-3 sr
// for KernerEnv's flared one; studio_small_03's brightest softbox has a 6.8e-3 sr core; potsdamer_platz's
// brightest patch is 5 times its surroundings.
struct SunDetectSettings {
    glm::dvec3 luminanceWeights = kRec709Luminance;
    double ringInnerDegrees = 2.0, ringOuterDegrees = 6.0; // the surroundings ring
    double ringFactor = 16.0;                              // T >= ringFactor * B (4 stops)
    int marginTexels = 1;                                  // margin around the core, texels
    // Compact: the core (texels above T) is at most this solid angle, or 4 peak texels on a grid too
    // coarse to resolve it. The disk is 6.8e-5 sr; a 1k capture blurs it over 4-9 pixels of 3.8e-5 sr.
    // 3e-3 sr (a cone of 1.8 degrees, 44 sun disks) leaves room for blur and flare (KernerEnv: 2e-3) and
    // rejects area lights (studio_small_03: 6.8e-3).
    double maxSolidAngle = 3e-3;
    // Dominant: the core holds more than this share of the light above T (excess over T times solid
    // angle) of all texels on the sphere.
    double minEnergyShare = 0.5;
    // Far brighter: E_perp / (kSunSolidAngle * max(B, S)) at least this (8 stops). The weakest sun here, a
    // sunset at 3 degrees elevation (venice_sunset), has 730-910 at every face size from 32 to 512; a
    // midday sun is ~1.6e9 cd/m2 against a sky of ~8000 (2e5). A bright lamp can pass too: the test is
    // "a compact source carrying a sun's share of light", which is what extraction needs.
    double minContrast = 300.0;
};

struct SunDetection {
    bool found = false;
    std::string reason; // why there is no sun ("" when found)
    DiskLight light;    // measured from the fill (valid when found)
    // Diagnostics, also filled when not found (when there is a candidate at all).
    double skyLuminance = 0.0;      // S: upper-hemisphere median
    double surroundLuminance = 0.0; // B: ring median around the peak
    double peakLuminance = 0.0;
    glm::dvec3 peakDirection{0.0, 1.0, 0.0};
    double contrast = 0.0;       // E_perp / (kSunSolidAngle * max(B, S)), when a region was measured
    double threshold = 0.0;      // T
    double coreSolidAngle = 0.0; // of the texels above T in the region
    double energyShare = 0.0;
    // The region and the fill (background RGB per region texel), indices of the SphereTexels it was
    // detected on.
    std::vector<std::size_t> region;
    std::vector<glm::vec3> fill;
    std::size_t texelCount = 0; // size of that grid
};

SunDetection detectSun(const SphereTexels& texels, const SunDetectSettings& settings = {});
SunDetection detectSun(const CubeMap& cube, const SunDetectSettings& settings = {});

// Writes the detection's fill into `texels` (which must be the grid it was detected on, with the same
// values) and returns the light whose illuminance is exactly the energy removed. Throws ibl::Error when
// the detection found no sun or does not fit the grid.
DiskLight extractSun(SphereTexels& texels, const SunDetection& detection,
                     const glm::dvec3& luminanceWeights = kRec709Luminance);
DiskLight extractSun(CubeMap& cube, const SunDetection& detection,
                     const glm::dvec3& luminanceWeights = kRec709Luminance);

// The light equivalent to an excess (RGB luminance removed, per region texel) on a grid: illuminance =
// luminance of sum(excess * omega); colour = that RGB sum / illuminance; direction = normalized integral
// of excess-luminance times direction (the energy-weighted centroid, exact within texels); angular
// radius = sqrt(2 <theta^2>) about that direction (a uniform disk of radius r has <theta^2> = r^2 / 2),
// each texel's own footprint counted as a small disk of its solid angle, so a one-texel sun gets the
// radius of its texel; solidAngle = the region's. Used by detection and extraction alike.
DiskLight diskLightFromExcess(const SphereTexels& texels, const std::vector<std::size_t>& region,
                              const std::vector<glm::dvec3>& excess,
                              const glm::dvec3& luminanceWeights = kRec709Luminance);

} // namespace ibl
