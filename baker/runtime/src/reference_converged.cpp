// The converged reference (runtime_reference.h renderConvergedReference). The environment's bilinear
// reconstruction is split, exactly (it is linear in the texels), into the bright texels and the dim rest:
// - the bright texels (a sun, a lamp: what leaves Monte Carlo noisy) are integrated deterministically,
//   over every texel footprint their bilinear spread reaches, on a sub-texel grid of exact fp64 solid
//   angles whose step is a fraction of the BRDF's local angular scale there (the lobe width near the
//   mirror direction, the distance from it further out);
// - the dim rest, whose dynamic range is small, by a fixed stratified set (Hammersley) of GGX visible
//   normal, cosine and environment samples (the dim texels' luminance x solid angle: a CDF built once per
//   environment) combined by the balance heuristic (Veach 1997).
// A lobe narrower than an eighth of a texel sees a bilinear environment that is flat across it: there the
// bright texels' specular part near the mirror direction is sampled with the visible normals as well
// (every sample lands on the same smooth patch), and only the rest is integrated on the grid.
#include "iblbake/core/error.h"
#include "iblbake/runtime/runtime_reference.h"
#include "reference_math.h"

#include <cube.h>

#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <set>

namespace ibl {

namespace {

using namespace reference;

// The centre of texel (x, y) of an n-texel face, in fp64.
glm::dvec3 footprintCentre(int face, int x, int y, int n) {
    return glm::normalize(glm::dvec3(cubeFaceDirection(face, (x + 0.5f) / float(n), (y + 0.5f) / float(n))));
}

// One texel footprint that the bilinear spread of a bright texel reaches.
struct Cell {
    int face, x, y;
    glm::dvec3 centre;
    double solidAngle, angle; // angle: the square root of the solid angle, radians
};

struct SplitEnvironment {
    int faceSize = 0;
    LdPyramid dim, bright; // level 0 only
    std::vector<Cell> cells;
    std::size_t brightTexels = 0;
    double texelAngle = 0.0; // of a texel at the face centre
    // Environment sampling of the dim rest: texel t (indices (face n + y) n + x) with probability
    // dimProbability[t], proportional to its luminance x solid angle, by inverting dimCdf; uniform in the
    // face plane within the texel. Empty when the dim rest is black.
    std::vector<double> dimProbability, dimCdf;

    bool sampleDim() const { return !dimCdf.empty(); }
    glm::dvec3 dimRadiance(const CubeCoord& c) const {
        return glm::dvec3(cubeSampleLevel(dim.data.data(), dim.layout, 0, c));
    }
    // The environment strategy's density per steradian at c: the texel's probability over its face-plane
    // area (2 / n)^2, times the plane-to-sphere Jacobian (1 + a^2 + b^2)^(3/2) at face coordinates (a, b).
    double dimPdf(const CubeCoord& c) const {
        if (!sampleDim()) return 0.0;
        const int n = faceSize;
        const int x = std::clamp(int(c.s * float(n)), 0, n - 1),
                  y = std::clamp(int(c.t * float(n)), 0, n - 1);
        const double a = 2.0 * c.s - 1.0, b = 2.0 * c.t - 1.0, r2 = 1.0 + a * a + b * b;
        return dimProbability[(std::size_t(c.face) * n + y) * n + x] * r2 * std::sqrt(r2) *
               (0.25 * double(n) * double(n));
    }
    // By inversion in two dimensions, as the other strategies' samples spread over their square: u.x picks
    // a texel row (face, y) by the rows' marginal CDF and the height within it, u.y the texel within the row
    // by its conditional CDF and the place across it. (Picking the texel by u.x alone, through one CDF over
    // every texel, made each half a rank-1 lattice along that CDF whose errors the two halves shared: on the
    // park map the estimate stated 0.33-0.49% for an actual 0.29-0.64%.)
    glm::dvec3 sampleDimDirection(glm::dvec2 u) const {
        const std::size_t n = std::size_t(faceSize), rows = 6 * n;
        // Row r spans dimCdf[r n] .. dimCdf[(r + 1) n]; the first row whose end is above u.x.
        std::size_t lo = 0, hi = rows - 1;
        while (lo < hi) {
            const std::size_t mid = (lo + hi) / 2;
            if (dimCdf[(mid + 1) * n] > u.x)
                hi = mid;
            else
                lo = mid + 1;
        }
        const std::size_t row = lo;
        const double rowStart = dimCdf[row * n], rowWidth = dimCdf[(row + 1) * n] - rowStart;
        const double fy = rowWidth > 0.0 ? std::clamp((u.x - rowStart) / rowWidth, 0.0, 1.0) : 0.5;
        const double target = rowStart + u.y * rowWidth;
        const auto first = dimCdf.begin() + std::ptrdiff_t(row * n);
        const auto it = std::upper_bound(first + 1, first + std::ptrdiff_t(n), target);
        const std::size_t x = std::size_t(it - first - 1);
        const double width = dimCdf[row * n + x + 1] - dimCdf[row * n + x];
        const double fx = width > 0.0 ? std::clamp((target - dimCdf[row * n + x]) / width, 0.0, 1.0) : 0.5;
        const int face = int(row / n);
        return glm::normalize(glm::dvec3(cubeFaceDirection(face, float((double(x) + fx) / double(n)),
                                                           float((double(row % n) + fy) / double(n)))));
    }
    glm::dvec3 brightRadiance(const glm::dvec3& l) const {
        return glm::dvec3(
            cubeSampleLevel(bright.data.data(), bright.layout, 0, cubeCoordFromDirection(vec3(l))));
    }
};

LdPyramid levelZero(const CubeMap& cube) {
    CubeMapChain chain;
    chain.levels.push_back(cube);
    return ldPyramidFromChain(chain);
}

} // namespace

std::vector<std::size_t> brightTexels(const CubeMap& cube, double factor, std::size_t maxCount) {
    const int n = cube.faceSize;
    double weighted = 0.0, total = 0.0;
    std::vector<std::pair<double, std::size_t>> candidates; // luminance, texel index
    for (int f = 0; f < 6; ++f)
        for (int y = 0; y < n; ++y)
            for (int x = 0; x < n; ++x) {
                const double omega = cubeTexelSolidAngle(x, y, n);
                const double lum = std::max(0.0, luminance(glm::dvec3(cube.faces[f].at(x, y))));
                weighted += lum * omega, total += omega;
                candidates.emplace_back(lum, (std::size_t(f) * n + y) * n + x);
            }
    const double threshold = factor * weighted / total;
    std::erase_if(candidates, [&](const auto& c) { return !(c.first > threshold); });
    if (candidates.size() > maxCount) { // the brightest ones
        std::nth_element(candidates.begin(), candidates.begin() + std::ptrdiff_t(maxCount), candidates.end(),
                         [](const auto& a, const auto& b) { return a.first > b.first; });
        candidates.resize(maxCount);
    }
    std::vector<std::size_t> out;
    for (const auto& c : candidates)
        out.push_back(c.second);
    std::sort(out.begin(), out.end());
    return out;
}

namespace {

SplitEnvironment splitEnvironment(const CubeMap& environment, const ConvergedReferenceSettings& settings) {
    const int n = environment.faceSize;
    const std::vector<std::size_t> brightList =
        brightTexels(environment, settings.brightFactor, settings.maxBrightTexels);
    SplitEnvironment e;
    e.faceSize = n;
    e.brightTexels = brightList.size();
    e.texelAngle = std::sqrt(double(cubeTexelSolidAngle(n / 2, n / 2, n)));
    CubeMap dim = environment, bright(n);
    std::set<std::size_t> reached;
    for (std::size_t index : brightList) {
        const int f = int(index / (std::size_t(n) * n)), y = int(index / n % n), x = int(index % n);
        bright.faces[f].at(x, y) = environment.faces[f].at(x, y);
        dim.faces[f].at(x, y) = glm::vec4(0.0f, 0.0f, 0.0f, 1.0f);
        // The 3 x 3 footprints around it, across face edges by direction.
        for (int dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx) {
                CubeCoord c = cubeCoordFromDirection(
                    cubeFaceDirection(f, (x + dx + 0.5f) / float(n), (y + dy + 0.5f) / float(n)));
                const int cx = std::clamp(int(c.s * float(n)), 0, n - 1),
                          cy = std::clamp(int(c.t * float(n)), 0, n - 1);
                reached.insert((std::size_t(c.face) * n + cy) * n + cx);
            }
    }
    for (std::size_t index : reached) {
        const int f = int(index / (std::size_t(n) * n)), y = int(index / n % n), x = int(index % n);
        const double u0 = -1.0 + 2.0 * x / n, v0 = -1.0 + 2.0 * y / n, step = 2.0 / n;
        const double omega = std::abs(cubeRectangleSolidAngleF64(u0, v0, u0 + step, v0 + step));
        e.cells.push_back({f, x, y,
                           glm::normalize(glm::dvec3(cubeFaceDirection(f, (x + 0.5f) / n, (y + 0.5f) / n))),
                           omega, std::sqrt(omega)});
    }
    e.dim = levelZero(dim);
    e.bright = levelZero(bright);
    // Environment sampling of the dim rest, unless it is nearly flat: within kFlatDim of its solid-angle
    // mean everywhere, environment sampling is about uniform over the sphere, which the cosine lobe beats
    // for every point (half of a uniform set falls below its horizon), and its samples only dilute the
    // other two strategies' (the sun test of tests/test_converged_reference.cpp over a uniform sky:
    // estimate 0.49% without, 0.52% with, at 1,024 samples).
    constexpr double kFlatDim = 4.0;
    const std::size_t count = 6 * std::size_t(n) * n;
    e.dimProbability.resize(count);
    double sum = 0.0, solidAngle = 0.0, brightest = 0.0;
    for (int f = 0; f < 6; ++f)
        for (int y = 0; y < n; ++y)
            for (int x = 0; x < n; ++x) {
                const double lum = reference::luminance(glm::dvec3(dim.faces[f].at(x, y)));
                const double omega = cubeTexelSolidAngle(x, y, n);
                const double weight = std::isfinite(lum) && lum > 0.0 ? lum * omega : 0.0;
                e.dimProbability[(std::size_t(f) * n + y) * n + x] = weight;
                sum += weight, solidAngle += omega;
                if (weight > 0.0) brightest = std::max(brightest, lum);
            }
    if (sum > 0.0 && brightest > kFlatDim * sum / solidAngle) {
        e.dimCdf.assign(count + 1, 0.0);
        for (std::size_t t = 0; t < count; ++t) {
            e.dimProbability[t] /= sum;
            e.dimCdf[t + 1] = e.dimCdf[t] + e.dimProbability[t];
        }
        e.dimCdf.back() = 1.0;
    } else {
        e.dimProbability.clear();
    }
    return e;
}

struct Integral {
    glm::dvec3 specular{0.0}, diffuse{0.0};
    // For the grid: the midpoint rule's error bound on the texels taken in one step, which no coarser
    // grid can show: h^2 / 24 |f''| with |f''| / f ~ (4 / scale)^2 for the specular part, (2/3) (angle /
    // scale)^2 of it, and ~1 per square radian for the diffuse part.
    glm::dvec3 singleStepBound{0.0};
    glm::dvec3 total() const { return specular + diffuse; }
};

// A lobe narrower than an eighth of a texel: the bright texels' specular part in the lobe's core (the
// footprints whose centre is within three texels of the mirror direction) is sampled, not gridded.
bool isNarrow(const PointMaterial& m, const SplitEnvironment& e) {
    return m.specular && 8.0 * m.alpha < e.texelAngle;
}
bool inCore(const glm::dvec3& footprintCentre, const glm::dvec3& R, const SplitEnvironment& e) {
    return glm::dot(footprintCentre, R) > std::cos(3.0 * e.texelAngle);
}

void addSample(Integral& out, const PointMaterial& m, const glm::dvec3& radiance, const glm::dvec3& l,
               double weight, bool specular, bool diffuse) {
    const double NoL = glm::dot(m.N, l);
    if (!(NoL > 0.0) || !(weight > 0.0)) return;
    glm::dvec3 s, d;
    m.evaluate(l, NoL, s, d);
    if (specular) out.specular += radiance * s * weight;
    if (diffuse) out.diffuse += radiance * d * weight;
}

// The sampled part at `samples` per strategy, the Hammersley sets rotated by `shift`: the dim rest by
// visible normals, cosine and the environment (balance heuristic: each sample weighs f / (samples x the
// sum of the three densities), which the environment's zero density where a dim texel is black leaves
// unbiased, the cosine density covering every direction above the horizon), and for a narrow lobe the
// bright texels' specular part in the lobe's core by visible normals alone.
Integral sampled(const PointMaterial& m, const SplitEnvironment& e, std::uint32_t samples, glm::dvec2 shift) {
    Integral out;
    const bool narrow = isNarrow(m, e);
    const glm::dvec3 R = m.reflected();
    auto dimSample = [&](const glm::dvec3& l) {
        const double NoL = glm::dot(m.N, l);
        if (!(NoL > 0.0)) return;
        const CubeCoord c = cubeCoordFromDirection(vec3(l));
        const double p = m.visibleNormalPdf(l) + NoL / kPi + e.dimPdf(c);
        if (p > 0.0) addSample(out, m, e.dimRadiance(c), l, 1.0 / (double(samples) * p), true, true);
    };
    for (std::uint32_t i = 0; i < samples; ++i) {
        dimSample(m.sampleVisibleNormalDirection(samplePoint(i, samples, shift)));
        dimSample(m.sampleCosineDirection(samplePoint(i, samples, shift + glm::dvec2(0.5, 0.25))));
        if (e.sampleDim())
            dimSample(e.sampleDimDirection(samplePoint(i, samples, shift + glm::dvec2(0.75, 0.125))));
        if (narrow) {
            const glm::dvec3 c =
                m.sampleVisibleNormalDirection(samplePoint(i, samples, shift + glm::dvec2(0.25, 0.5)));
            const double p = m.visibleNormalPdf(c);
            const CubeCoord t = cubeCoordFromDirection(vec3(c));
            const int n = e.faceSize;
            const glm::dvec3 footprint = footprintCentre(t.face, std::clamp(int(t.s * float(n)), 0, n - 1),
                                                         std::clamp(int(t.t * float(n)), 0, n - 1), n);
            if (inCore(footprint, R, e))
                addSample(out, m, e.brightRadiance(c), c, p > 0.0 ? 1.0 / (double(samples) * p) : 0.0, true,
                          false);
        }
    }
    return out;
}

// The bright texels: every footprint they reach, on a sub-texel grid whose step is 1 / `stepsPerScale` of
// the BRDF's local angular scale, and (`half`) on the grid of half as many steps, in one pass: a footprint
// taken in one step on the finer grid is taken in one step on the coarser too, the same value, computed
// once. GGX's D changes by about 4 dtheta / max(alpha, theta / 4) over dtheta radians of l at theta from
// the mirror direction; the diffuse lobe's scale is a radian.
Integral gridded(const PointMaterial& m, const SplitEnvironment& e, double stepsPerScale, Integral& half) {
    Integral out;
    const bool narrow = isNarrow(m, e);
    const glm::dvec3 R = m.reflected();
    const int n = e.faceSize;
    // The footprint on an S x S grid of sub-texels.
    auto cellIntegral = [&](const Cell& cell, int S, bool specular) {
        Integral sum;
        const double step = 2.0 / (double(n) * S);
        for (int j = 0; j < S; ++j)
            for (int i = 0; i < S; ++i) {
                const double u0 = -1.0 + (cell.x * S + i) * step, v0 = -1.0 + (cell.y * S + j) * step;
                const double omega = std::abs(cubeRectangleSolidAngleF64(u0, v0, u0 + step, v0 + step));
                const glm::dvec3 l = glm::normalize(glm::dvec3(cubeFaceDirection(
                    cell.face, float((u0 + 0.5 * step + 1.0) / 2.0), float((v0 + 0.5 * step + 1.0) / 2.0))));
                addSample(sum, m, e.brightRadiance(l), l, omega, specular, true);
            }
        return sum;
    };
    auto add = [](Integral& to, const Integral& part) {
        to.specular += part.specular;
        to.diffuse += part.diffuse;
    };
    for (const Cell& cell : e.cells) {
        if (glm::dot(cell.centre, m.N) < -1.5 * cell.angle) continue; // wholly below the horizon
        const double theta = std::acos(std::clamp(glm::dot(cell.centre, R), -1.0, 1.0));
        const bool specular = m.specular && !(narrow && inCore(cell.centre, R, e));
        const double scale = specular ? std::min(std::max(m.alpha, theta / 4.0), 1.0) : 1.0;
        auto steps = [&](double perScale) {
            return int(std::clamp(std::ceil(perScale * cell.angle / scale), 1.0, 64.0));
        };
        const int S = steps(stepsPerScale), halfS = steps(stepsPerScale / 2.0);
        if (S == 1) {
            Integral single;
            addSample(single, m, e.brightRadiance(cell.centre), cell.centre, cell.solidAngle, specular, true);
            add(out, single);
            add(half, single);
            const double ratio = cell.angle / scale;
            out.singleStepBound += (2.0 / 3.0) * ratio * ratio * glm::abs(single.specular) +
                                   cell.solidAngle / 24.0 * glm::abs(single.diffuse);
            continue;
        }
        add(out, cellIntegral(cell, S, specular));
        add(half, cellIntegral(cell, halfS, specular));
    }
    return out;
}

// E(NoV) of one alpha on 512 steps of NoV, linearly interpolated: the points of a roughness column share
// their alpha, and E is smooth in NoV.
class AlbedoTables {
  public:
    AlbedoTables(std::span<const ShadingPoint> points, double minAlpha, std::uint32_t samples)
        : samples_(samples) {
        std::set<double> alphas;
        for (const ShadingPoint& p : points) {
            const double r = std::clamp(double(p.perceptualRoughness), 0.0, 1.0);
            alphas.insert(std::max(r * r, minAlpha));
        }
        if (alphas.size() > 64) return; // no shared columns: per point
        std::vector<std::pair<double, std::vector<double>*>> columns;
        for (double alpha : alphas) {
            std::vector<double>& t = tables_[alpha];
            t.resize(kSteps + 1);
            columns.emplace_back(alpha, &t);
        }
        // Every entry is its own integral: the same values in any order, on every core.
        tbb::parallel_for(std::size_t(0), columns.size() * (kSteps + 1), [&](std::size_t k) {
            const auto& [alpha, t] = columns[k / (kSteps + 1)];
            const std::size_t i = k % (kSteps + 1);
            (*t)[i] = directionalAlbedo(std::max(double(i) / kSteps, 1e-4), alpha, samples);
        });
    }
    double operator()(double NoV, double alpha) const {
        auto it = tables_.find(alpha);
        if (it == tables_.end()) return directionalAlbedo(NoV, alpha, samples_);
        const double x = std::clamp(NoV, 0.0, 1.0) * kSteps;
        const int i = std::min(int(x), kSteps - 1);
        return it->second[std::size_t(i)] +
               (x - i) * (it->second[std::size_t(i) + 1] - it->second[std::size_t(i)]);
    }

  private:
    static constexpr int kSteps = 512;
    std::uint32_t samples_;
    std::map<double, std::vector<double>> tables_;
};

} // namespace

namespace {

// A point's sampled or gridded part: its value and its estimated error (per channel).
struct Part {
    glm::dvec3 diffuse{0.0}, specular{0.0}, error{0.0};
    glm::dvec3 total() const { return diffuse + specular; }
};

// Two independent halves of the samples (different rotations): their half difference has the size of the
// mean's sampling error.
Part sampledPart(const PointMaterial& m, const SplitEnvironment& e, std::uint32_t samples) {
    const Integral first = sampled(m, e, samples / 2, {0.0, 0.0});
    const Integral second = sampled(m, e, samples / 2, {0.61803398875, 0.41421356237});
    return {0.5 * (first.diffuse + second.diffuse), 0.5 * (first.specular + second.specular),
            glm::abs(0.5 * (second.total() - first.total()))};
}

// The grid at two steps: the midpoint rule's error falls 4x per halved step, so the difference bounds it.
Part griddedPart(const PointMaterial& m, const SplitEnvironment& e, double stepsPerScale) {
    Integral half;
    const Integral grid = gridded(m, e, stepsPerScale, half);
    return {grid.diffuse, grid.specular, glm::abs(grid.total() - half.total()) + grid.singleStepBound};
}

// The sampled part in batches that add up (renderAdaptiveReference): each batch brings two halves of fresh
// rotations, and the sums over all batches so far give the mean and the half difference of all samples.
struct SampledSums {
    Integral a, b;             // sums of sample weights x values of each half over the batches
    std::uint32_t perHalf = 0; // samples per half over the batches
    void add(const PointMaterial& m, const SplitEnvironment& e, std::uint32_t batchPerHalf,
             std::uint32_t batch) {
        // Batch j's rotations: the R2 sequence (Roberts 2018) for the first half, the fixed-effort's offset
        // from it for the second, so that batch 0 is the fixed effort's sample set.
        const glm::dvec2 shift =
            glm::fract(double(batch) * glm::dvec2(0.7548776662466927, 0.5698402909980532));
        const Integral first = sampled(m, e, batchPerHalf, shift);
        const Integral second =
            sampled(m, e, batchPerHalf, glm::fract(shift + glm::dvec2(0.61803398875, 0.41421356237)));
        a.diffuse += double(batchPerHalf) * first.diffuse;
        a.specular += double(batchPerHalf) * first.specular;
        b.diffuse += double(batchPerHalf) * second.diffuse;
        b.specular += double(batchPerHalf) * second.specular;
        perHalf += batchPerHalf;
    }
    Part part() const {
        const double n = 2.0 * double(perHalf);
        return {(a.diffuse + b.diffuse) / n, (a.specular + b.specular) / n,
                glm::abs(a.total() - b.total()) / n};
    }
};

} // namespace

ConvergedReference renderConvergedReference(const CubeMap& environment, std::span<const ShadingPoint> points,
                                            const RuntimeOptions& options,
                                            const ConvergedReferenceSettings& settings) {
    if (settings.samples < 4) throw Error("converged reference: fewer than 4 samples per strategy");
    const SplitEnvironment e = splitEnvironment(environment, settings);
    const AlbedoTables albedo(points, settings.minAlpha, settings.albedoSamples);
    ConvergedReference out;
    out.brightTexels = e.brightTexels;
    out.results.resize(points.size());
    out.errorEstimate.resize(points.size());
    tbb::parallel_for(std::size_t(0), points.size(), [&](std::size_t k) {
        const PointMaterial m(points[k], options, settings.minAlpha, albedo);
        const Part sampledRest = sampledPart(m, e, settings.samples);
        const Part grid = griddedPart(m, e, settings.stepsPerScale);
        out.results[k] = {sampledRest.diffuse + grid.diffuse, sampledRest.specular + grid.specular};
        out.errorEstimate[k] = sampledRest.error + grid.error;
    });
    return out;
}

AdaptiveReference renderAdaptiveReference(const CubeMap& environment, std::span<const ShadingPoint> points,
                                          std::span<const int> groupOfPoint, const RuntimeOptions& options,
                                          const ConvergedReferenceSettings& settings,
                                          const AdaptiveReferenceSettings& adaptive,
                                          const ReferenceProgress& progress) {
    if (adaptive.firstSamples < 4) throw Error("converged reference: fewer than 4 samples per strategy");
    if (groupOfPoint.size() != points.size())
        throw Error("converged reference: " + std::to_string(groupOfPoint.size()) + " group ids for " +
                    std::to_string(points.size()) + " points");
    int groupCount = 0;
    for (int g : groupOfPoint) {
        if (g < 0) throw Error("converged reference: a negative group id");
        groupCount = std::max(groupCount, g + 1);
    }
    const SplitEnvironment e = splitEnvironment(environment, settings);
    const AlbedoTables albedo(points, settings.minAlpha, settings.albedoSamples);
    std::vector<std::vector<std::size_t>> members(static_cast<std::size_t>(groupCount));
    for (std::size_t k = 0; k < points.size(); ++k)
        members[std::size_t(groupOfPoint[k])].push_back(k);

    const std::uint32_t maxSamples = std::max(adaptive.firstSamples, settings.samples * 16);
    const double maxSteps = 4.0 * settings.stepsPerScale;
    AdaptiveReference out;
    out.groupSamples.assign(std::size_t(groupCount), adaptive.firstSamples);
    out.groupStepsPerScale.assign(std::size_t(groupCount), settings.stepsPerScale);
    out.groupErrorEstimate.assign(std::size_t(groupCount), 0.0);
    std::vector<SampledSums> sampledRest(points.size());
    std::vector<Part> grid(points.size());
    std::vector<std::uint32_t> batches(std::size_t(groupCount), 0); // per group: batches taken
    // What the next round computes for each group: its samples, its grid, or nothing (done).
    std::vector<bool> refineSamples(std::size_t(groupCount), true), refineGrid(std::size_t(groupCount), true);
    int groupsDone = 0;
    // The time estimate: seconds per point-sample of the rounds so far (a grid round counted as a round of
    // the group's samples), times the point-samples the groups left need if their estimates keep falling at
    // the rate of their last doubling (one over the square root of the samples before a second round: on
    // the park map they fell faster at first, and that guess was up to 3x the time left).
    double seconds = 0.0, pointSamplesDone = 0.0;
    std::vector<double> previousEstimate(std::size_t(groupCount), 0.0);
    while (groupsDone < groupCount) {
        const auto roundStart = std::chrono::steady_clock::now();
        std::vector<std::size_t> work; // points of the groups that refine a part
        for (int g = 0; g < groupCount; ++g)
            if (refineSamples[std::size_t(g)] || refineGrid[std::size_t(g)]) {
                work.insert(work.end(), members[std::size_t(g)].begin(), members[std::size_t(g)].end());
                pointSamplesDone += double(members[std::size_t(g)].size()) *
                                    double(refineSamples[std::size_t(g)] && batches[std::size_t(g)] > 0
                                               ? out.groupSamples[std::size_t(g)] / 2
                                               : out.groupSamples[std::size_t(g)]);
            }
        tbb::parallel_for(std::size_t(0), work.size(), [&](std::size_t i) {
            const std::size_t k = work[i];
            const std::size_t g = std::size_t(groupOfPoint[k]);
            const PointMaterial m(points[k], options, settings.minAlpha, albedo);
            // The first batch has the group's first samples; each later one as many as all before it.
            if (refineSamples[g])
                sampledRest[k].add(m, e, std::max(out.groupSamples[g] / 2 - sampledRest[k].perHalf, 1u),
                                   batches[g]);
            if (refineGrid[g]) grid[k] = griddedPart(m, e, out.groupStepsPerScale[g]);
        });
        seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - roundStart).count();
        for (int g = 0; g < groupCount; ++g)
            if (refineSamples[std::size_t(g)]) ++batches[std::size_t(g)];
        double pointSamplesLeft = 0.0;
        for (int g = 0; g < groupCount; ++g) {
            const std::size_t gi = std::size_t(g);
            if (!refineSamples[gi] && !refineGrid[gi]) continue;
            double sampledError = 0.0, gridError = 0.0, sum = 0.0;
            for (std::size_t k : members[gi]) {
                const Part rest = sampledRest[k].part();
                sampledError += luminance(rest.error);
                gridError += luminance(grid[k].error);
                sum += luminance(rest.total() + grid[k].total());
            }
            const double relative = (sampledError + gridError) / std::max(sum, 1e-300);
            out.groupErrorEstimate[gi] = relative;
            const bool canSample = out.groupSamples[gi] < maxSamples,
                       canGrid = out.groupStepsPerScale[gi] < maxSteps;
            refineSamples[gi] = refineGrid[gi] = false;
            if (kEstimateMargin * relative <= adaptive.targetError || (!canSample && !canGrid)) {
                ++groupsDone;
                continue;
            }
            // The larger part is refined: halving the smaller one could not bring the sum under the target.
            if (canSample && (sampledError >= gridError || !canGrid)) {
                out.groupSamples[gi] *= 2;
                refineSamples[gi] = true;
            } else {
                out.groupStepsPerScale[gi] *= 2.0;
                refineGrid[gi] = true;
            }
            // Halvings of the estimate per doubling of the samples, measured once there are two rounds.
            const double rate = previousEstimate[gi] > relative && relative > 0.0
                                    ? std::clamp(std::log2(previousEstimate[gi] / relative), 0.5, 1.0)
                                    : 0.5;
            previousEstimate[gi] = relative;
            const double needed =
                std::clamp(std::pow(kEstimateMargin * relative / adaptive.targetError, 1.0 / rate) *
                               double(out.groupSamples[gi] / (refineSamples[gi] ? 2 : 1)),
                           double(out.groupSamples[gi]), double(maxSamples));
            pointSamplesLeft += double(members[gi].size()) *
                                (needed - double(out.groupSamples[gi] / (refineSamples[gi] ? 2 : 1)));
        }
        if (progress)
            progress(groupsDone, groupCount, seconds / std::max(pointSamplesDone, 1.0) * pointSamplesLeft);
    }
    ConvergedReference& r = out.reference;
    r.brightTexels = e.brightTexels;
    r.results.resize(points.size());
    r.errorEstimate.resize(points.size());
    for (std::size_t k = 0; k < points.size(); ++k) {
        const Part rest = sampledRest[k].part();
        r.results[k] = {rest.diffuse + grid[k].diffuse, rest.specular + grid[k].specular};
        r.errorEstimate[k] = rest.error + grid[k].error;
    }
    return out;
}

} // namespace ibl
