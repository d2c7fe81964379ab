// Photometric statistics of an environment (docs/conventions.md "Units and calibration"): what `iblbake
// inspect` prints and what calibration measures. Everything is integrated over the sphere with exact
// per-texel solid angles, on either the source cube (the ingested SourceEnvironment) or a lat-long image's
// own pixel grid.
//
// Luminance is Y = w . RGB with the working space's luminance weights (Rec.709 / lin_rec709 by default:
// 0.2126 R + 0.7152 G + 0.0722 B). Directions follow docs/conventions.md: right-handed, +Y up.
#pragma once

#include "iblbake/baker/latlong_pixels.h"
#include "iblbake/core/cubemap.h"
#include "iblbake/core/image.h"
#include "iblbake/core/numeric.h"

#include <cstddef>
#include <memory>
#include <vector>

#include <glm/vec3.hpp>

namespace ibl {

// An environment as a set of texels on the unit sphere with exact geometry in double: a lat-long's computed
// on demand (nothing per texel is stored, so a 16k lat-long costs no extra memory), a cube's read from a
// table of one face quadrant shared by every view of that face size. It refers to, and does not own,
// the pixels of either
//   - a cube map: texel (face f, column i, row j) has index (f * N + j) * N + i; its footprint is the
//     spherical quadrilateral under the face-plane square of kernels/cube.h, or
//   - a lat-long image: pixel (x, y) has index y * W + x; its footprint is its cell in the pixel grid of
//     the placement it was read with (latlong_pixels.h), the same grid the ingest resamples from.
class CubeTexelGeometry; // src/calibration/cube_texel_geometry.h

class SphereTexels {
  public:
    // Views that may write (setRgb) and read-only views, chosen by the constness of the argument.
    explicit SphereTexels(CubeMap& cube);
    explicit SphereTexels(const CubeMap& cube);
    // `placement` must be resolved (Centre or OpenExr: IngestReport::latLongPixels). Throws ibl::Error for
    // an image smaller than 2 x 2.
    SphereTexels(ImageRGBA& latlong, LatLongPixels placement);
    SphereTexels(const ImageRGBA& latlong, LatLongPixels placement);

    bool isCube() const { return cube_ != nullptr; }
    int faceSize() const { return cube_ ? cube_->faceSize : 0; } // 0 for a lat-long
    std::size_t size() const { return size_; }
    // Same geometry (kind and resolution): indices of one are valid in the other.
    bool sameGridAs(const SphereTexels& other) const;

    bool writable() const { return writable_; }
    glm::vec3 rgb(std::size_t i) const;
    void setRgb(std::size_t i, const glm::vec3& value); // alpha untouched; throws on a read-only view

    // Exact solid angle of the texel's footprint (steradians); they sum to 4 pi.
    double solidAngle(std::size_t i) const;
    // Integral over the footprint of the unit direction, d omega (Arvo's vector irradiance of a spherical
    // polygon; exact). Its length / solidAngle <= 1; its direction is the footprint's centroid direction.
    glm::dvec3 vectorSolidAngle(std::size_t i) const;
    // Unit direction through the footprint's centroid (normalized vectorSolidAngle).
    glm::dvec3 direction(std::size_t i) const;
    // Exact integral over the footprint of max(0, d.y) d omega: the texel's weight in the illuminance of
    // an upward-facing (+Y) surface. They sum to pi.
    double upwardCosine(std::size_t i) const;
    // The texels sharing an edge or a corner with texel i (across cube edges and the lat-long seam; the
    // pole rows of a lat-long touch the pixel half a turn away), without i and without repeats.
    void neighbours(std::size_t i, std::vector<std::size_t>& out) const;

    // A cube view's cube and texel table (null for a lat-long view), for loops over many texels that walk
    // the faces (src/calibration/texel_loop.h) instead of dividing every index as the accessors above do.
    const CubeMap* cubeMap() const { return cube_; }
    const CubeTexelGeometry* cubeGeometry() const { return cubeGeometry_.get(); }

  private:
    struct CubeTexel {
        int face, i, j;
    };
    CubeTexel cubeTexel(std::size_t i) const;
    CubeMap* cube_ = nullptr;
    std::shared_ptr<const CubeTexelGeometry> cubeGeometry_; // the cube's face size's
    ImageRGBA* latlong_ = nullptr;
    LatLongPixels placement_ = LatLongPixels::Centre;
    std::size_t size_ = 0;
    bool writable_ = false;
    glm::vec4& texel(std::size_t i) const;
};

// The sums over the sphere (what a calibration reads of the statistics, computeEnvironmentTotals below).
struct EnvironmentTotals {
    double solidAngle = 0.0; // sum of the texels' solid angles (4 pi up to rounding; a self-check)
    // Luminance (cd/m2 once calibrated, else relative units) over all texels.
    double minLuminance = 0.0, maxLuminance = 0.0;
    double meanLuminance = 0.0; // solid-angle-weighted arithmetic mean over the sphere
    // Illuminance (lux once calibrated) on a horizontal surface facing +Y: integral over the upper
    // hemisphere of Y cos(theta) d omega, with exact per-texel cosine integrals.
    double upwardIlluminance = 0.0;
};

// The totals, and what needs each texel's luminance kept: the log average, the low percentile and the
// exposures built on them.
struct EnvironmentStats : EnvironmentTotals {
    std::size_t texels = 0;
    double logMeanLuminance = 0.0; // solid-angle-weighted geometric mean over texels with Y > 0
    // Dynamic range in stops: log2(max / P), P the 0.1th percentile of the positive luminances, the
    // percentile taken by solid angle (the luminance below which 0.1 % of the positive texels' solid
    // angle lies; SOURCES.md counts pixels instead, which weights a lat-long's poles more).
    double lowPercentileLuminance = 0.0;
    double dynamicRangeStops = 0.0;
    // Suggested EV100 (Frostbite eq. 11 / 69, S = 100, K = 12.5): log2(Lavg * 100 / 12.5) with Lavg the
    // log-average (geometric mean) luminance, Frostbite 5.1.1's "average log luminance", which a sun
    // cannot dominate. ev100FromMean uses the arithmetic mean instead. Both NaN for a black environment.
    double ev100 = 0.0;
    double ev100FromMean = 0.0;
};

EnvironmentStats computeEnvironmentStats(const SphereTexels& texels,
                                         const glm::dvec3& luminanceWeights = kRec709Luminance);
EnvironmentStats computeEnvironmentStats(const CubeMap& cube,
                                         const glm::dvec3& luminanceWeights = kRec709Luminance);
// What a calibration reads of the statistics, with the same sums, so the same values as
// computeEnvironmentStats(), without its per-texel samples, logarithms and percentile: at 256-px faces
// 3.6 ms of CPU instead of 7.0 ms (bench: cubeTotals, cubeStatistics, idle), and no 3 MB array first touched.
EnvironmentTotals computeEnvironmentTotals(const SphereTexels& texels,
                                           const glm::dvec3& luminanceWeights = kRec709Luminance);
// `latlong` is an equirect image in the docs/conventions.md mapping, measured on its own pixel grid
// (`placement`).
EnvironmentStats computeLatLongStats(const ImageRGBA& latlong, LatLongPixels placement,
                                     const glm::dvec3& luminanceWeights = kRec709Luminance);

// Frostbite eq. 11 with S = 100, K = 12.5: EV100 = log2(L * 100 / 12.5) = log2(8 L); NaN for L <= 0.
double ev100FromLuminance(double averageLuminance);

// Solid-angle-weighted mean luminance over the cap within `capDegrees` of +Y (zenith luminance as a spot
// meter pointed straight up reads it, averaged over the cap to be robust to noise and to a lat-long's
// pole), leaving out the texels in `exclude` (a detected sun's region). A grid too coarse to have a texel
// centroid in the cap uses the texels nearest +Y. 0 when nothing is left. Used by --sky-luminance.
double zenithLuminance(const SphereTexels& texels, double capDegrees,
                       const glm::dvec3& luminanceWeights = kRec709Luminance,
                       const std::vector<std::size_t>& exclude = {});

} // namespace ibl
