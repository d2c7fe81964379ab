// Exact texel geometry on the sphere (SphereTexels) and the photometric statistics built on it.
//
// Cube texels: the tabulated geometry of cube_texel_geometry.h.
//
// Lat-long cells are rectangles in (longitude phi, z = sin latitude), where d omega = d phi dz, and every
// integral needed separates: solid angle dphi dz, upward cosine dphi (z1^2 - z0^2) / 2, direction
// integral from the antiderivative of sqrt(1 - z^2).
#include "iblbake/baker/environment_stats.h"
#include "iblbake/core/numeric.h"

#include "cube_texel_geometry.h"
#include "iblbake/core/error.h"
#include "luminance_bins.h"
#include "texel_loop.h"

#include <cube.h>

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h> // parallel_deterministic_reduce

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

namespace ibl {

namespace {

// ---- lat-long geometry (the placement's pixel grid, latlong_pixels.h) ----

struct LatLongCell {
    double phi0, phi1; // longitude range, phi0 < phi1
    double z0, z1;     // z = sin(latitude) range, z0 < z1
};

LatLongCell latLongCell(int x, int y, int w, int h, LatLongPixels placement) {
    // u grows as longitude falls: phi = (0.5 - u) 2 pi (docs/conventions.md).
    const double phiA = (0.5 - latLongPixelEdge(placement, x, w)) * 2.0 * kPi,
                 phiB = (0.5 - latLongPixelEdge(placement, x + 1, w)) * 2.0 * kPi;
    const double zTop = y <= 0 ? 1.0 : std::cos(kPi * latLongPixelEdge(placement, y, h));
    const double zBottom = y + 1 >= h ? -1.0 : std::cos(kPi * latLongPixelEdge(placement, y + 1, h));
    return {phiB, phiA, zBottom, zTop};
}

// Antiderivative of sqrt(1 - z^2).
double sqrtOneMinusSquareIntegral(double z) {
    z = std::clamp(z, -1.0, 1.0);
    return 0.5 * (z * std::sqrt(1.0 - z * z) + std::asin(z));
}

// z1^2 - z0^2 without cancellation.
double squareDifference(double z1, double z0) {
    return (z1 - z0) * (z1 + z0);
}

// Cube texel index i = face * N^2 + rest, for a cube of `size` texels.
struct CubeIndex {
    std::size_t face, rest; // rest: the index within the face, j * N + i
};

CubeIndex splitCubeIndex(std::size_t i, int faceSize, std::size_t size) {
    // In 32 bits whenever the cube's indices fit (every cube a bake makes: 6 * 4096^2 < 2^32), where a
    // division is several times cheaper than in 64 bits; every accessor of a cube view divides.
    const std::size_t n = std::size_t(faceSize);
    if (size <= std::numeric_limits<std::uint32_t>::max()) {
        const std::uint32_t nn = std::uint32_t(n * n), k = std::uint32_t(i);
        return {k / nn, k % nn};
    }
    return {i / (n * n), i % (n * n)};
}

} // namespace

// ---- SphereTexels ----

SphereTexels::SphereTexels(CubeMap& cube) : cube_(&cube), writable_(true) {
    if (cube.faceSize <= 0) throw Error("environment: empty cube map");
    size_ = 6 * std::size_t(cube.faceSize) * std::size_t(cube.faceSize);
    cubeGeometry_ = CubeTexelGeometry::of(cube.faceSize);
}

SphereTexels::SphereTexels(const CubeMap& cube) : SphereTexels(const_cast<CubeMap&>(cube)) {
    writable_ = false;
}

SphereTexels::SphereTexels(ImageRGBA& latlong, LatLongPixels placement)
    : latlong_(&latlong), placement_(placement), writable_(true) {
    if (placement == LatLongPixels::Auto) throw Error("environment: internal: unresolved lat-long placement");
    if (latlong.width < 2 || latlong.height < 2)
        throw Error("environment: a lat-long image needs at least 2x2 pixels, got " +
                    std::to_string(latlong.width) + "x" + std::to_string(latlong.height));
    size_ = std::size_t(latlong.width) * std::size_t(latlong.height);
}

SphereTexels::SphereTexels(const ImageRGBA& latlong, LatLongPixels placement)
    : SphereTexels(const_cast<ImageRGBA&>(latlong), placement) {
    writable_ = false;
}

bool SphereTexels::sameGridAs(const SphereTexels& other) const {
    if (isCube() != other.isCube()) return false;
    if (isCube()) return cube_->faceSize == other.cube_->faceSize;
    return latlong_->width == other.latlong_->width && latlong_->height == other.latlong_->height &&
           placement_ == other.placement_;
}

glm::vec4& SphereTexels::texel(std::size_t i) const {
    if (cube_) {
        const CubeIndex t = splitCubeIndex(i, cube_->faceSize, size_);
        return cube_->faces[t.face].pixels[t.rest];
    }
    return latlong_->pixels[i];
}

glm::vec3 SphereTexels::rgb(std::size_t i) const {
    return glm::vec3(texel(i));
}

void SphereTexels::setRgb(std::size_t i, const glm::vec3& value) {
    if (!writable_) throw Error("environment: internal: write through a read-only view");
    glm::vec4& t = texel(i);
    t = glm::vec4(value, t.w);
}

SphereTexels::CubeTexel SphereTexels::cubeTexel(std::size_t i) const {
    const CubeIndex t = splitCubeIndex(i, cube_->faceSize, size_);
    const std::uint32_t n = std::uint32_t(cube_->faceSize), r = std::uint32_t(t.rest);
    return {int(t.face), int(r % n), int(r / n)};
}

double SphereTexels::solidAngle(std::size_t i) const {
    if (cube_) {
        const CubeTexel t = cubeTexel(i);
        return cubeGeometry_->solidAngle(t.i, t.j);
    }
    const int w = latlong_->width, h = latlong_->height;
    const LatLongCell c = latLongCell(int(i % std::size_t(w)), int(i / std::size_t(w)), w, h, placement_);
    return (c.phi1 - c.phi0) * (c.z1 - c.z0);
}

glm::dvec3 SphereTexels::vectorSolidAngle(std::size_t i) const {
    if (cube_) {
        const CubeTexel t = cubeTexel(i);
        return cubeGeometry_->vectorSolidAngle(t.face, t.i, t.j);
    }
    const int w = latlong_->width, h = latlong_->height;
    const LatLongCell c = latLongCell(int(i % std::size_t(w)), int(i / std::size_t(w)), w, h, placement_);
    const double s = sqrtOneMinusSquareIntegral(c.z1) - sqrtOneMinusSquareIntegral(c.z0);
    return {s * (std::cos(c.phi0) - std::cos(c.phi1)), 0.5 * (c.phi1 - c.phi0) * squareDifference(c.z1, c.z0),
            s * (std::sin(c.phi1) - std::sin(c.phi0))};
}

glm::dvec3 SphereTexels::direction(std::size_t i) const {
    return glm::normalize(vectorSolidAngle(i));
}

double SphereTexels::upwardCosine(std::size_t i) const {
    if (cube_) {
        const CubeTexel t = cubeTexel(i);
        return cubeGeometry_->upwardCosine(t.face, t.i, t.j);
    }
    const int w = latlong_->width, h = latlong_->height;
    const LatLongCell c = latLongCell(int(i % std::size_t(w)), int(i / std::size_t(w)), w, h, placement_);
    const double z0 = std::max(c.z0, 0.0), z1 = std::max(c.z1, 0.0);
    return 0.5 * (c.phi1 - c.phi0) * squareDifference(z1, z0);
}

void SphereTexels::neighbours(std::size_t i, std::vector<std::size_t>& out) const {
    out.clear();
    auto push = [&](std::size_t k) {
        if (k != i && std::find(out.begin(), out.end(), k) == out.end()) out.push_back(k);
    };
    if (cube_) {
        const int n = cube_->faceSize;
        const std::size_t nn = std::size_t(n) * std::size_t(n);
        const int face = int(i / nn), r = int(i % nn), ti = r % n, tj = r / n;
        for (int dj = -1; dj <= 1; ++dj)
            for (int di = -1; di <= 1; ++di) {
                const int ii = ti + di, jj = tj + dj;
                if (ii >= 0 && ii < n && jj >= 0 && jj < n) {
                    push(std::size_t(face) * nn + std::size_t(jj) * std::size_t(n) + std::size_t(ii));
                    continue;
                }
                // Off the face: the texel hit by the direction through the extended face plane.
                const CubeCoord c = cubeCoordFromDirection(
                    cubeFaceDirection(face, (float(ii) + 0.5f) / float(n), (float(jj) + 0.5f) / float(n)));
                const int ci = std::clamp(int(std::floor(c.s * float(n))), 0, n - 1);
                const int cj = std::clamp(int(std::floor(c.t * float(n))), 0, n - 1);
                push(std::size_t(c.face) * nn + std::size_t(cj) * std::size_t(n) + std::size_t(ci));
            }
        return;
    }
    const int w = latlong_->width, h = latlong_->height;
    const int x = int(i % std::size_t(w)), y = int(i / std::size_t(w));
    for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
            int xx = x + dx, yy = y + dy;
            if (yy < 0 || yy >= h) { // over the pole: the same row, half a turn away
                yy = yy < 0 ? 0 : h - 1;
                xx += w / 2;
            }
            xx = ((xx % w) + w) % w;
            push(std::size_t(yy) * std::size_t(w) + std::size_t(xx));
        }
}

// ---- statistics ----

double ev100FromLuminance(double averageLuminance) {
    if (!(averageLuminance > 0.0)) return std::numeric_limits<double>::quiet_NaN();
    return std::log2(averageLuminance * 100.0 / 12.5);
}

namespace {

// A positive texel as (luminance, solid angle).
using LuminanceSample = std::pair<float, float>;

// The luminance below which `target` of the positive-luminance solid angle lies (texels as (luminance,
// solid angle) pairs, consumed; `binCounts` counts them per binOf). Only the darkest texels are ordered: the
// answer lies among them unless the solid angles are very uneven, when the whole list is sorted; either
// way the result is the full sort's. The darkest are first moved to the front (the texels in the lowest
// bins that hold at least as many), so the selection runs over a few thousand texels instead of all.
float lowPercentile(std::vector<LuminanceSample>& positive,
                    const std::array<std::uint32_t, kLuminanceBins>& binCounts, double target) {
    std::size_t prefix = std::min(positive.size(), std::max<std::size_t>(1024, positive.size() / 64));
    std::size_t lastBin = 0, dark = binCounts[0];
    while (dark < prefix)
        dark += binCounts[++lastBin];
    std::partition(positive.begin(), positive.end(),
                   [&](const LuminanceSample& s) { return luminanceBin(s.first) <= lastBin; });
    for (;;) {
        // The prefix smallest pairs lie in the front part while it holds that many: all of its pairs are
        // smaller than all of the others.
        const auto end = prefix <= dark ? positive.begin() + std::ptrdiff_t(dark) : positive.end();
        std::nth_element(positive.begin(), positive.begin() + std::ptrdiff_t(prefix - 1), end);
        std::sort(positive.begin(), positive.begin() + std::ptrdiff_t(prefix));
        double acc = 0.0;
        for (std::size_t k = 0; k < prefix; ++k) {
            acc += positive[k].second;
            if (acc >= target) return positive[k].first;
        }
        if (prefix == positive.size()) return positive.back().first;
        prefix = std::min(positive.size(), prefix * 8);
    }
}

struct Sums {
    double omega = 0.0, energy = 0.0, upward = 0.0;
    double logOmega = 0.0, logSum = 0.0;
    double minY = std::numeric_limits<double>::infinity(), maxY = -std::numeric_limits<double>::infinity();
};

// The sums over the texels; with `samples` (one per texel), also each texel's (luminance, solid angle),
// luminance -1 when not positive, and the log sums. Deterministic: the same split into ranges on any
// number of threads, so the same sums to the last bit (a calibration factor from them reaches every
// product, which must not depend on the machine), with or without `samples`.
Sums sumTexels(const SphereTexels& texels, const glm::dvec3& weights, LuminanceSample* samples) {
    using Range = tbb::blocked_range<std::size_t>;
    return tbb::parallel_deterministic_reduce(
        Range(0, texels.size(), 4096), Sums{},
        [&](const Range& range, Sums a) {
            forEachTexel(texels, range.begin(), range.end(), [&](std::size_t i, const auto& texel) {
                const double y = glm::dot(weights, glm::dvec3(texel.rgb()));
                const double omega = texel.solidAngle();
                a.omega += omega;
                a.energy += y * omega;
                a.upward += y * texel.upwardCosine();
                a.minY = std::min(a.minY, y);
                a.maxY = std::max(a.maxY, y);
                if (!samples) return;
                samples[i] = {y > 0.0 ? float(y) : -1.0f, float(omega)};
                if (y > 0.0) {
                    a.logOmega += omega;
                    a.logSum += omega * std::log(y);
                }
            });
            return a;
        },
        [](Sums a, const Sums& b) {
            a.omega += b.omega;
            a.energy += b.energy;
            a.upward += b.upward;
            a.logOmega += b.logOmega;
            a.logSum += b.logSum;
            a.minY = std::min(a.minY, b.minY);
            a.maxY = std::max(a.maxY, b.maxY);
            return a;
        });
}

EnvironmentTotals totalsOf(const Sums& s) {
    EnvironmentTotals t;
    t.solidAngle = s.omega;
    t.minLuminance = s.minY;
    t.maxLuminance = s.maxY;
    t.meanLuminance = s.energy / s.omega;
    t.upwardIlluminance = s.upward;
    return t;
}

} // namespace

EnvironmentTotals computeEnvironmentTotals(const SphereTexels& texels, const glm::dvec3& weights) {
    return totalsOf(sumTexels(texels, weights, nullptr));
}

EnvironmentStats computeEnvironmentStats(const SphereTexels& texels, const glm::dvec3& weights) {
    std::vector<LuminanceSample> samples(texels.size());
    const Sums s = sumTexels(texels, weights, samples.data());
    const EnvironmentTotals totals = totalsOf(s);

    EnvironmentStats st;
    static_cast<EnvironmentTotals&>(st) = totals;
    st.texels = texels.size();
    st.logMeanLuminance = s.logOmega > 0.0 ? std::exp(s.logSum / s.logOmega) : 0.0;

    // 0.1th percentile of the positive luminances by solid angle. The positive samples are moved to the
    // front of `samples` in their order, not copied: a second array as large (3 MB at 256-px faces) is
    // memory first touched, a page fault per 4 KB (ingest/read_image.cpp).
    std::array<std::uint32_t, kLuminanceBins> binCounts{};
    std::size_t positiveCount = 0;
    for (const LuminanceSample& sample : samples)
        if (sample.first >= 0.0f) {
            samples[positiveCount++] = sample;
            ++binCounts[luminanceBin(sample.first)];
        }
    std::vector<LuminanceSample> positive = std::move(samples);
    positive.resize(positiveCount);
    if (!positive.empty()) {
        st.lowPercentileLuminance = lowPercentile(positive, binCounts, 0.001 * s.logOmega);
        st.dynamicRangeStops = std::log2(st.maxLuminance / st.lowPercentileLuminance);
    }
    st.ev100 = ev100FromLuminance(st.logMeanLuminance);
    st.ev100FromMean = ev100FromLuminance(st.meanLuminance);
    return st;
}

EnvironmentStats computeEnvironmentStats(const CubeMap& cube, const glm::dvec3& weights) {
    return computeEnvironmentStats(SphereTexels(cube), weights);
}

EnvironmentStats computeLatLongStats(const ImageRGBA& latlong, LatLongPixels placement,
                                     const glm::dvec3& weights) {
    return computeEnvironmentStats(SphereTexels(latlong, placement), weights);
}

double zenithLuminance(const SphereTexels& texels, double capDegrees, const glm::dvec3& weights,
                       const std::vector<std::size_t>& exclude) {
    // Texels whose centroid lies in the cap; on a grid too coarse to have any, the ones nearest +Y. On a
    // cube, a cap narrower than 45 degrees holds +Y's texels only: every other face's texel centroids lie
    // more than 45 degrees from +Y (a side face's nearest point, the middle of its top edge, is at 45),
    // and +Y's central texels are nearer than that, so the nearest texels are +Y's too; the other faces
    // are skipped (their texels come before and after +Y's, so the sums' order is unchanged).
    const std::size_t faceTexels = texels.isCube() ? texels.size() / 6 : 0;
    const bool plusYOnly = texels.isCube() && capDegrees < 45.0;
    const std::size_t first = plusYOnly ? 2 * faceTexels : 0,
                      last = plusYOnly ? 3 * faceTexels : texels.size();
    // The cosines in parallel (a maximum does not depend on the order); the sums below stay in texel
    // order, over the few texels of the cap, so the result is the serial loop's to the last bit.
    using Range = tbb::blocked_range<std::size_t>;
    std::vector<double> cosines(last - first);
    const double nearest = tbb::parallel_reduce(
        Range(first, last, 4096), -1.0,
        [&](const Range& range, double m) {
            forEachTexel(texels, range.begin(), range.end(), [&](std::size_t i, const auto& texel) {
                const glm::dvec3 v = texel.vectorSolidAngle();
                cosines[i - first] = v.y / glm::length(v);
                m = std::max(m, cosines[i - first]);
            });
            return m;
        },
        [](double a, double b) { return std::max(a, b); });
    const double cosCap = std::min(std::cos(capDegrees * kPi / 180.0), nearest - 1e-12);
    std::vector<std::size_t> skip = exclude;
    std::sort(skip.begin(), skip.end());
    double energy = 0.0, omega = 0.0;
    for (std::size_t i = first; i < last; ++i) {
        if (cosines[i - first] < cosCap || std::binary_search(skip.begin(), skip.end(), i)) continue;
        const double w = texels.solidAngle(i);
        energy += glm::dot(weights, glm::dvec3(texels.rgb(i))) * w;
        omega += w;
    }
    return omega > 0.0 ? energy / omega : 0.0;
}

} // namespace ibl
