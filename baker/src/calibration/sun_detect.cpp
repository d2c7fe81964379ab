// Sun detection and measurement (the algorithm is described in iblbake/baker/sun.h).
#include "iblbake/baker/sun.h"
#include "iblbake/core/error.h"
#include "iblbake/core/numeric.h"

#include "luminance_bins.h"
#include "texel_loop.h"

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h> // parallel_deterministic_reduce

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <deque>
#include <functional>
#include <limits>
#include <unordered_map>
#include <unordered_set>

namespace ibl {

namespace {

// Angle between unit vectors, accurate for small angles too.
double angleBetween(const glm::dvec3& a, const glm::dvec3& b) {
    return std::atan2(glm::length(glm::cross(a, b)), glm::dot(a, b));
}

// Solid-angle-weighted median of (value, weight) pairs (consumed): the first value, in ascending order,
// at which the running weight reaches half the total; 0 when empty. Found by selection (a weighted
// quickselect): nth_element splits the range where the answer lies at its middle until a short range is
// left, which is sorted. The weights are summed part by part rather than in sorted order, which changes
// only their rounding.
double weightedMedian(std::vector<std::pair<float, double>>& samples) {
    if (samples.empty()) return 0.0;
    double total = 0.0;
    for (const auto& s : samples)
        total += s.second;
    const double half = 0.5 * total;
    const auto weightOf = [&](std::size_t begin, std::size_t end) {
        double w = 0.0;
        for (std::size_t k = begin; k < end; ++k)
            w += samples[k].second;
        return w;
    };
    constexpr std::size_t kSorted = 64; // a range this short is sorted
    std::size_t lo = 0, hi = samples.size();
    double acc = 0.0; // weight of the samples before lo
    const auto at = [&](std::size_t k) { return samples.begin() + std::ptrdiff_t(k); };
    while (hi - lo > kSorted) {
        const std::size_t mid = lo + (hi - lo) / 2;
        std::nth_element(at(lo), at(mid), at(hi));
        const double below = acc + weightOf(lo, mid);
        if (below >= half) {
            hi = mid;
        } else {
            acc = below;
            lo = mid;
        }
    }
    std::sort(at(lo), at(hi));
    for (std::size_t k = lo; k < hi; ++k) {
        acc += samples[k].second;
        if (acc >= half) return samples[k].first;
    }
    return samples[hi - 1].first;
}

std::string format(const char* fmt, double a, double b = 0.0) {
    char buf[256];
    std::snprintf(buf, sizeof buf, fmt, a, b);
    return buf;
}

// Texels reachable from `seed` through neighbours for which `accept` holds (the seed is not tested).
template <class Accept>
std::vector<std::size_t> floodFill(const SphereTexels& texels, std::size_t seed, Accept accept) {
    std::vector<std::size_t> out;
    std::unordered_set<std::size_t> seen{seed};
    std::deque<std::size_t> queue{seed};
    std::vector<std::size_t> nb;
    while (!queue.empty()) {
        const std::size_t i = queue.front();
        queue.pop_front();
        out.push_back(i);
        texels.neighbours(i, nb);
        for (std::size_t k : nb)
            if (!seen.count(k) && accept(k)) {
                seen.insert(k);
                queue.push_back(k);
            }
    }
    return out;
}

// The sun's region: its core is the texels above `threshold` linked to `seed` by chains of core texels
// at most `margin` steps apart (margin 1: plain 8-connectivity); the region is the core and every texel
// within `margin` steps of it. So every texel just outside the region is at or below the threshold, and
// the region takes in the spill of a sun blurred by capture or resampling, whose energy a tight
// threshold region would leave behind. Returns false once the core's solid angle exceeds
// `maxCoreSolidAngle`.
bool growSunRegion(const SphereTexels& texels, std::size_t seed, const std::vector<float>& lum,
                   float threshold, int margin, double maxCoreSolidAngle, std::vector<std::size_t>& region,
                   double& coreOmega) {
    region.clear();
    coreOmega = 0.0;
    std::unordered_set<std::size_t> inRegion, inCore{seed};
    std::deque<std::size_t> cores{seed};
    std::vector<std::size_t> frontier, next, nb;
    auto addToRegion = [&](std::size_t k) {
        if (inRegion.insert(k).second) region.push_back(k);
    };
    while (!cores.empty()) {
        const std::size_t c = cores.front();
        cores.pop_front();
        addToRegion(c);
        coreOmega += texels.solidAngle(c);
        if (coreOmega > maxCoreSolidAngle) return false;
        frontier.assign(1, c);
        std::unordered_set<std::size_t> seen{c};
        for (int depth = 0; depth < margin; ++depth) {
            next.clear();
            for (std::size_t f : frontier) {
                texels.neighbours(f, nb);
                for (std::size_t k : nb) {
                    if (!seen.insert(k).second) continue;
                    next.push_back(k);
                    addToRegion(k);
                    if (lum[k] > threshold && inCore.insert(k).second) cores.push_back(k);
                }
            }
            frontier.swap(next);
        }
    }
    return true;
}

// Harmonic fill of `region` from its outer boundary: every region texel ends up the average of its
// neighbours (Gauss-Seidel on the graph Laplacian, Dirichlet values on the boundary). The result is a
// convex combination of boundary values.
std::vector<glm::vec3> harmonicFill(const SphereTexels& texels, const std::vector<std::size_t>& region) {
    std::unordered_map<std::size_t, std::size_t> slot; // texel -> index in region
    for (std::size_t k = 0; k < region.size(); ++k)
        slot.emplace(region[k], k);
    // Per region texel: its neighbours inside the region (as slots) and the sum of those outside (fixed).
    struct Links {
        std::vector<std::size_t> inner;
        glm::dvec3 fixedSum{0.0};
        int count = 0;
    };
    std::vector<Links> links(region.size());
    std::vector<std::size_t> nb;
    glm::dvec3 boundarySum(0.0);
    int boundaryCount = 0;
    for (std::size_t k = 0; k < region.size(); ++k) {
        texels.neighbours(region[k], nb);
        for (std::size_t n : nb) {
            auto it = slot.find(n);
            if (it != slot.end()) {
                links[k].inner.push_back(it->second);
            } else {
                const glm::dvec3 v(texels.rgb(n));
                links[k].fixedSum += v;
                boundarySum += v;
                ++boundaryCount;
            }
            ++links[k].count;
        }
    }
    const glm::dvec3 start = boundaryCount > 0 ? boundarySum / double(boundaryCount) : glm::dvec3(0.0);
    std::vector<glm::dvec3> f(region.size(), start);
    const double scale = std::max({start.x, start.y, start.z, 1e-30});
    for (int iteration = 0; iteration < 20000; ++iteration) {
        double change = 0.0;
        for (std::size_t k = 0; k < region.size(); ++k) {
            glm::dvec3 sum = links[k].fixedSum;
            for (std::size_t n : links[k].inner)
                sum += f[n];
            const glm::dvec3 next = sum / double(std::max(1, links[k].count));
            const glm::dvec3 d = glm::abs(next - f[k]);
            change = std::max({change, d.x, d.y, d.z});
            f[k] = next;
        }
        if (change <= 1e-9 * scale) break;
    }
    std::vector<glm::vec3> out(region.size());
    for (std::size_t k = 0; k < region.size(); ++k)
        out[k] = glm::vec3(glm::max(f[k], glm::dvec3(0.0)));
    return out;
}

using TexelRange = tbb::blocked_range<std::size_t>;
constexpr std::size_t kTexelsPerTask = 4096;

// What one pass over the texels gathers: the brightest texel (the first of equals) and the solid angle
// of the upper hemisphere's texels per luminance bin.
struct LuminanceScan {
    float peak = -std::numeric_limits<float>::infinity();
    std::size_t peakIndex = 0;
    std::array<double, kLuminanceBins> skyWeight{};
};

// Fills lum (luminance per texel) and upper (the texel's direction integral points above the horizon).
// Deterministic: the same split into ranges on any number of threads, so the same sums to the last bit.
LuminanceScan scanLuminance(const SphereTexels& texels, const glm::dvec3& weights, std::vector<float>& lum,
                            std::vector<std::uint8_t>& upper) {
    return tbb::parallel_deterministic_reduce(
        TexelRange(0, texels.size(), kTexelsPerTask), LuminanceScan{},
        [&](const TexelRange& range, LuminanceScan scan) {
            forEachTexel(texels, range.begin(), range.end(), [&](std::size_t i, const auto& texel) {
                const float y = float(glm::dot(weights, glm::dvec3(texel.rgb())));
                lum[i] = y;
                if (y > scan.peak) {
                    scan.peak = y;
                    scan.peakIndex = i;
                }
                upper[i] = texel.vectorSolidAngleY() > 0.0;
                if (upper[i]) scan.skyWeight[luminanceBin(y)] += texel.solidAngle();
            });
            return scan;
        },
        [](LuminanceScan a, const LuminanceScan& b) {
            if (b.peak > a.peak) {
                a.peak = b.peak;
                a.peakIndex = b.peakIndex;
            }
            for (std::size_t k = 0; k < kLuminanceBins; ++k)
                a.skyWeight[k] += b.skyWeight[k];
            return a;
        });
}

// Solid-angle-weighted median of the upper hemisphere's luminances (weightedMedian's definition): the bin
// where the running weight reaches half comes from the scan; only that bin's texels are gathered and
// sorted.
double skyMedian(const SphereTexels& texels, const LuminanceScan& scan, const std::vector<float>& lum,
                 const std::vector<std::uint8_t>& upper) {
    double total = 0.0;
    for (double w : scan.skyWeight)
        total += w;
    if (!(total > 0.0)) return 0.0;
    const double half = 0.5 * total;
    double before = 0.0; // weight of the bins below `bin`
    std::size_t bin = 0;
    while (bin + 1 < kLuminanceBins && before + scan.skyWeight[bin] < half)
        before += scan.skyWeight[bin++];
    // Gathered in parallel in any order: the sort orders them.
    tbb::enumerable_thread_specific<std::vector<std::pair<float, double>>> gathered;
    tbb::parallel_for(TexelRange(0, texels.size(), kTexelsPerTask), [&](const TexelRange& range) {
        std::vector<std::pair<float, double>>& mine = gathered.local();
        forEachTexel(texels, range.begin(), range.end(), [&](std::size_t i, const auto& texel) {
            if (upper[i] && luminanceBin(lum[i]) == bin) mine.emplace_back(lum[i], texel.solidAngle());
        });
    });
    std::vector<std::pair<float, double>> samples;
    for (const auto& part : gathered)
        samples.insert(samples.end(), part.begin(), part.end());
    std::sort(samples.begin(), samples.end());
    for (const auto& [value, weight] : samples) {
        before += weight;
        if (before >= half) return value;
    }
    return samples.empty() ? 0.0 : samples.back().first;
}

// The solid-angle-weighted excess over the threshold of the texels above it: sum of (lum - threshold)
// omega where lum > t, t the threshold in float (deterministic, as scanLuminance).
double excessAbove(const SphereTexels& texels, const std::vector<float>& lum, float t, double threshold) {
    return tbb::parallel_deterministic_reduce(
        TexelRange(0, texels.size(), kTexelsPerTask), 0.0,
        [&](const TexelRange& range, double sum) {
            forEachTexel(texels, range.begin(), range.end(), [&](std::size_t i, const auto& texel) {
                if (lum[i] > t) sum += (double(lum[i]) - threshold) * texel.solidAngle();
            });
            return sum;
        },
        std::plus<double>());
}

} // namespace

double DiskLight::elevationDegrees() const {
    return std::asin(std::clamp(direction.y, -1.0, 1.0)) / kDegree;
}

double DiskLight::azimuthDegrees() const {
    return std::atan2(direction.x, direction.z) / kDegree;
}

double DiskLight::angularRadiusDegrees() const {
    return angularRadius / kDegree;
}

double DiskLight::diskSolidAngle() const {
    return 2.0 * kPi * (1.0 - std::cos(angularRadius));
}

DiskLight diskLightFromExcess(const SphereTexels& texels, const std::vector<std::size_t>& region,
                              const std::vector<glm::dvec3>& excess, const glm::dvec3& weights) {
    if (excess.size() != region.size()) throw Error("sun: internal: excess and region sizes differ");
    DiskLight light;
    glm::dvec3 rgb(0.0), axis(0.0);
    std::vector<glm::dvec3> dirs(region.size());
    std::vector<double> w(region.size()), omegas(region.size());
    for (std::size_t k = 0; k < region.size(); ++k) {
        const double omega = texels.solidAngle(region[k]);
        const glm::dvec3 v = texels.vectorSolidAngle(region[k]);
        const double y = glm::dot(weights, excess[k]);
        rgb += excess[k] * omega;
        light.solidAngle += omega;
        axis += y * v;
        dirs[k] = glm::normalize(v);
        w[k] = y * omega;
        omegas[k] = omega;
    }
    light.illuminance = glm::dot(weights, rgb);
    if (!(light.illuminance > 0.0) || !(glm::length(axis) > 0.0)) {
        light.illuminance = 0.0;
        light.color = glm::dvec3(1.0);
        return light;
    }
    light.color = rgb / light.illuminance;
    light.direction = glm::normalize(axis);
    double moment = 0.0, total = 0.0;
    for (std::size_t k = 0; k < region.size(); ++k) {
        const double theta = angleBetween(dirs[k], light.direction);
        moment += w[k] * (theta * theta + omegas[k] / (2.0 * kPi));
        total += w[k];
    }
    light.angularRadius = total > 0.0 ? std::sqrt(2.0 * moment / total) : 0.0;
    return light;
}

SunDetection detectSun(const SphereTexels& texels, const SunDetectSettings& settings) {
    SunDetection det;
    const std::size_t n = texels.size();
    det.texelCount = n;
    const glm::dvec3& wt = settings.luminanceWeights;

    // One pass: luminance per texel, the peak, and the sky's weight per luminance bin.
    std::vector<float> lum(n);
    std::vector<std::uint8_t> upper(n);
    const LuminanceScan scan = scanLuminance(texels, wt, lum, upper);
    const std::size_t peak = scan.peakIndex;
    det.peakLuminance = lum[peak];
    det.peakDirection = texels.direction(peak);
    if (!(det.peakLuminance > 0.0)) {
        det.reason = "the environment is black";
        return det;
    }

    // 1. Sky level: upper-hemisphere median.
    det.skyLuminance = skyMedian(texels, scan, lum, upper);

    // 2. Surroundings: median over the ring around the peak.
    {
        const double outer = settings.ringOuterDegrees * kDegree, inner = settings.ringInnerDegrees * kDegree;
        const std::vector<std::size_t> disk = floodFill(texels, peak, [&](std::size_t k) {
            return angleBetween(texels.direction(k), det.peakDirection) <= outer;
        });
        std::vector<std::pair<float, double>> samples;
        for (std::size_t k : disk)
            if (angleBetween(texels.direction(k), det.peakDirection) >= inner)
                samples.emplace_back(lum[k], texels.solidAngle(k));
        det.surroundLuminance = weightedMedian(samples);
    }
    const double reference = std::max(det.surroundLuminance, det.skyLuminance);
    det.threshold = std::max(settings.ringFactor * det.surroundLuminance,
                             std::sqrt(det.peakLuminance * det.surroundLuminance));

    // 3. The region: texels above the threshold around the peak, and a margin.
    const float t = float(det.threshold);
    if (!(det.peakLuminance > det.threshold)) {
        det.reason =
            format("the brightest texel is only %.3g times its surroundings (a sun is more than %.3g)",
                   det.peakLuminance / std::max(det.surroundLuminance, 1e-30), settings.ringFactor);
        return det;
    }
    // Compactness limit: the setting, or 4 peak texels on a grid too coarse to resolve it.
    const double maxCore = std::max(settings.maxSolidAngle, 4.0 * texels.solidAngle(peak));
    if (!growSunRegion(texels, peak, lum, t, settings.marginTexels, maxCore, det.region,
                       det.coreSolidAngle)) {
        det.reason =
            format("the region above the sun threshold is larger than %.3g sr (an area light or sky, "
                   "not a sun)",
                   maxCore);
        det.region.clear();
        return det;
    }
    double regionExcess = 0.0;
    for (std::size_t k : det.region)
        if (lum[k] > t) regionExcess += (double(lum[k]) - det.threshold) * texels.solidAngle(k);
    const double allExcess = excessAbove(texels, lum, t, det.threshold);
    det.energyShare = allExcess > 0.0 ? regionExcess / allExcess : 1.0;
    if (det.energyShare <= settings.minEnergyShare) {
        det.reason =
            format("the brightest region holds only %.0f%% of the light above its threshold (several "
                   "sources, none dominant)",
                   100.0 * det.energyShare);
        det.region.clear();
        return det;
    }

    // 4-5. Background fill and the light it implies.
    det.fill = harmonicFill(texels, det.region);
    std::vector<glm::dvec3> excess(det.region.size());
    for (std::size_t k = 0; k < det.region.size(); ++k) {
        const glm::dvec3 before(texels.rgb(det.region[k]));
        excess[k] = before - glm::min(before, glm::dvec3(det.fill[k]));
    }
    det.light = diskLightFromExcess(texels, det.region, excess, wt);

    // 6. Far brighter than the sky: the light's luminance were it a sun-sized disk, over the reference.
    det.contrast = reference > 0.0 ? det.light.illuminance / (kSunSolidAngle * reference) : HUGE_VAL;
    if (!(det.contrast >= settings.minContrast)) {
        det.reason =
            format("the brightest region is only %.3g times as bright as its surroundings, as a sun-sized "
                   "disk (a sun is at least %.3g)",
                   det.contrast, settings.minContrast);
        det.region.clear();
        det.fill.clear();
        return det;
    }
    det.found = true;
    return det;
}

SunDetection detectSun(const CubeMap& cube, const SunDetectSettings& settings) {
    return detectSun(SphereTexels(cube), settings);
}

} // namespace ibl
