// Brute-force reference of one LD level: every source texel, solid-angle weighted, fp64 accumulation.
// Used by tests and the accuracy report, never by a production path.
#include "iblbake/baker/specular.h"
#include "iblbake/core/numeric.h"

#include "bright_split.h"
#include "iblbake/runtime/runtime_reference.h" // brightTexels

#include <cube.h>
#include <ld.h>
#include <sampling.h>

#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <span>

namespace ibl {

namespace {

glm::dvec3 texelCentre(int face, int x, int y, int w) {
    return glm::normalize(glm::dvec3(cubeFaceDirection(face, (x + 0.5f) / w, (y + 0.5f) / w)));
}

// The LD weight's integrand pi D(h) NoL (as a^2 / d^2 NoL, see below) times the solid angle omega of a cell
// around unit direction l.
double cellWeight(const glm::dvec3& nrm, const glm::dvec3& l, double omega, double a2) {
    double NoL = glm::dot(nrm, l);
    if (NoL <= 0.0) return 0.0;
    double NoH = glm::dot(nrm, glm::normalize(nrm + l));
    double d = NoH * NoH * (a2 - 1.0) + 1.0;
    return a2 / (d * d) * NoL * omega;
}

double typicalTexelAngle(int w) {
    return std::sqrt(4.0 * kPi / (6.0 * double(w) * w)); // in radians
}

// texelWeight (at gridFactor 40 or less) of a w-texel face's texel whose centre lies at a cosine below the
// returned value from the lobe is the single cell of texel centre and exact texel solid angle: its grid is
// 1 x 1 from max(angle, alpha) >= gridFactor x texel angle on (the margin covers acos's rounding), and the
// closed form applies within three texels only. 2 when that holds for every texel.
double oneCellCosine(int w, double alpha) {
    const double reach = 40.0 * typicalTexelAngle(w) * (1.0 + 1e-9);
    if (alpha > reach) return 2.0;
    return reach >= kPi ? -2.0 : std::cos(reach);
}

// texelWeight's grid size: D's relative change across a sub-texel is about 4 (size / max(angle, alpha)),
// kept under ~0.1 by gridFactor 40 (the accuracy check halves it).
int gridSize(int w, double alpha, double angle, double gridFactor) {
    return int(std::clamp(std::ceil(gridFactor * typicalTexelAngle(w) / std::max(angle, alpha)), 1.0, 256.0));
}

// The exact solid angle of texel (x, y) of a w-texel face, in fp64 (in float, the four-term difference
// loses ~1e-3 of a 256-px face's texel).
double texelSolidAngle(int x, int y, int w) {
    const double step = 2.0 / w, u = -1.0 + x * step, v = -1.0 + y * step;
    return std::abs(cubeRectangleSolidAngleF64(u, v, u + step, v + step));
}

// fn(l, omega) for each cell of texel (f, x, y) of a w-texel face on an S x S grid (S <= 256), row by row:
// the cell's centre direction and exact solid angle. A cell's solid angle is the four-term difference of
// cubeAreaElementF64 at its corners; neighbours share corners, so each row of corners is evaluated once: one
// atan2 a cell instead of four (the atan2s were most of the references' time).
template <class Fn>
void forEachCell(int f, int x, int y, int w, int S, Fn&& fn) {
    const double step = 2.0 / (double(w) * S);
    std::array<double, 257> rows[2];
    double *lower = rows[0].data(), *upper = rows[1].data();
    auto cornerRow = [&](int j, double* row) {
        for (int i = 0; i <= S; ++i)
            row[i] = cubeAreaElementF64(-1.0 + (x * S + i) * step, -1.0 + (y * S + j) * step);
    };
    cornerRow(0, lower);
    for (int j = 0; j < S; ++j) {
        cornerRow(j + 1, upper);
        for (int i = 0; i < S; ++i) {
            const double omega = lower[i] - upper[i] - lower[i + 1] + upper[i + 1];
            const float s = float((x * S + i + 0.5) / (double(w) * S)),
                        t = float((y * S + j + 0.5) / (double(w) * S));
            fn(glm::normalize(glm::dvec3(cubeFaceDirection(f, s, t))), std::abs(omega));
        }
        std::swap(lower, upper);
    }
}

// Within three texels of a lobe under a quarter texel wide, D is too peaked for any grid: the closed-form
// small-angle integral (kernels/ld.h, checked against quadrature in tests) is exact to O(texel angle^2).
// narrowLobeTexelWeight integrates D NoL, the grid below pi D NoL (a^2 / d^2 NoL): the same measure.
std::optional<double> closedFormWeight(const glm::dvec3& nrm, int f, int x, int y, int w, double alpha,
                                       double angle) {
    const float texelSize = 2.0f / float(w);
    if (!narrowLobeClosedFormApplies(float(alpha), texelSize, float(angle))) return std::nullopt;
    return kPi * double(narrowLobeTexelWeight(frameFromNormal(vec3(nrm)), f, -1.0f + x * texelSize,
                                              -1.0f + y * texelSize, texelSize, float(alpha)));
}

// The LD weight of one source texel of constant radiance for the lobe around `nrm` (N = V = R): the
// integral of pi D(h) NoL over the texel (Listing 19's estimator's expectation, up to normalization),
// on a gridSize x gridSize grid of exact sub-texel solid angles, S growing as the lobe gets narrow compared
// with the texel and the texel near the lobe; or in closed form (closedFormWeight).
double texelWeight(const glm::dvec3& nrm, int f, int x, int y, int w, double alpha, double angle,
                   double gridFactor = 40.0) {
    if (const std::optional<double> closedForm = closedFormWeight(nrm, f, x, y, w, alpha, angle))
        return *closedForm;
    const double a2 = alpha * alpha;
    double weight = 0.0;
    forEachCell(f, x, y, w, gridSize(w, alpha, angle, gridFactor),
                [&](const glm::dvec3& l, double omega) { weight += cellWeight(nrm, l, omega, a2); });
    return weight;
}

// texelWeight of one output texel t at many directions (the footprint mean, the kernel symmetric in n and
// l): t's cells for each grid size up to kCachedGrid are computed once (directions and solid angles, the
// same values texelWeight computes each time), which leaves a dot product and a square root per cell.
class OutputTexelWeights {
  public:
    OutputTexelWeights(int face, int x, int y, int n, double alpha)
        : face_(face), x_(x), y_(y), n_(n), alpha_(alpha), texelSize_(2.0f / float(n)),
          corners_(faceSquareCorners(face, -1.0f + x * texelSize_, -1.0f + y * texelSize_, texelSize_)),
          cells_(kCachedGrid + 1) {}
    double operator()(const glm::dvec3& l, double angle, double gridFactor) {
        // closedFormWeight with t's corners computed once.
        if (narrowLobeClosedFormApplies(float(alpha_), texelSize_, float(angle)))
            return kPi * double(narrowLobeCornersWeight(frameFromNormal(vec3(l)), corners_, float(alpha_)));
        const int S = gridSize(n_, alpha_, angle, gridFactor);
        if (S > kCachedGrid) return texelWeight(l, face_, x_, y_, n_, alpha_, angle, gridFactor);
        std::vector<Cell>& cells = cells_[std::size_t(S)];
        if (cells.empty())
            forEachCell(face_, x_, y_, n_, S, [&](const glm::dvec3& c, double omega) {
                cells.push_back({c, omega});
            });
        const double a2 = alpha_ * alpha_;
        double weight = 0.0;
        for (const Cell& c : cells)
            weight += cellWeight(l, c.direction, c.omega, a2);
        return weight;
    }

  private:
    static constexpr int kCachedGrid = 64; // 64 x 64 cells: 128 kB
    struct Cell {
        glm::dvec3 direction;
        double omega;
    };
    int face_, x_, y_, n_;
    double alpha_;
    float texelSize_;
    FaceSquareCorners corners_;
    std::vector<std::vector<Cell>> cells_; // by grid size
};

// A source texel and its radiance, as the references integrate it exactly; its centre direction and exact
// solid angle (the single cell of texelWeight's grid far from the lobe), computed once for every output
// texel.
struct SourceTexel {
    int face, x, y;
    glm::dvec3 radiance;
    glm::dvec3 centre{0.0};
    double solidAngle = 0.0;
};

SourceTexel sourceTexel(int face, int x, int y, int w, const glm::dvec3& radiance) {
    return {face, x, y, radiance, texelCentre(face, x, y, w), texelSolidAngle(x, y, w)};
}

std::vector<SourceTexel> texelList(const CubeMap& source, std::span<const std::size_t> indices) {
    const int w = source.faceSize;
    const std::size_t faceTexels = std::size_t(w) * std::size_t(w);
    std::vector<SourceTexel> out;
    for (std::size_t k : indices)
        out.push_back(sourceTexel(int(k / faceTexels), int(k % std::size_t(w)),
                                  int(k % faceTexels / std::size_t(w)), w,
                                  glm::dvec3(source.faces[k / faceTexels].pixels[k % faceTexels])));
    return out;
}

// What is averaged over an output texel where ldFootprintApplies (kernels/ld.h): the excess of the bright
// texels (bright_split.h, above SpecularSettings' threshold, up to the references' own count
// kMaxBrightTexels, whatever count a bake splits off); the residual is taken at the texel's centre, like
// every texel of other levels. A bake that splits off fewer texels than pass the threshold leaves the others'
// narrow lobes at their centres, and is measured so.
struct FootprintSplit {
    CubeMap residual;
    std::vector<SourceTexel> excess;
};

FootprintSplit footprintSplit(const CubeMap& source) {
    BrightSplit split =
        splitBrightTexels(source, SpecularSettings{}.brightThreshold, std::uint32_t(kMaxBrightTexels));
    FootprintSplit out{std::move(split.residual), {}};
    for (std::size_t i = 0; i < split.bright.entries.size(); i += IBL_BRIGHT_ENTRY_FLOATS) {
        const float* e = &split.bright.entries[i];
        out.excess.push_back(
            sourceTexel(int(e[7]), int(e[8]), int(e[9]), source.faceSize, glm::dvec3(e[4], e[5], e[6])));
    }
    return out;
}

// The part of output texel (face, x, y) of an n-texel level that `texels` (of a w-texel source) give: the
// sums of radiance x weight and of the weights, at the texel's centre, or with `overFootprint` averaged over
// the texel. The footprint mean of a texel b is integral_b G_t(l) dl / Omega_t with G_t(l) = integral_t
// pi D NoL dn (the kernel is symmetric in n and l): texelWeight with the output texel as "the texel" around
// l, on an S x S grid of b, S = 4 source texel / alpha up to 64 (G_t changes over about alpha at t's
// edges), 2 x 2 beyond two texels. `coarse` is the same at half the grids (the error estimate: where a grid
// does not resolve alpha the rule converges only linearly, so the estimate is the whole difference); at the
// centre, a texel far enough for a single cell (oneCellCosine) has the same weight on both grids, computed
// once.
struct TexelsPart {
    glm::dvec3 radiance{0.0};
    double weight = 0.0;
    void add(double texelShare, const glm::dvec3& texelRadiance) {
        radiance += texelShare * texelRadiance;
        weight += texelShare;
    }
};
struct TexelsParts {
    TexelsPart fine, coarse;
};

TexelsParts texelsParts(int w, std::span<const SourceTexel> texels, int face, int x, int y, int n,
                        double alpha, bool overFootprint, bool withCoarse) {
    const glm::dvec3 centre = texelCentre(face, x, y, n);
    const double sourceStep = 2.0 / w;
    const double texelOmega = texelSolidAngle(x, y, n);
    const double oneCell = oneCellCosine(w, alpha);
    OutputTexelWeights outputTexelWeight(face, x, y, n, alpha);
    auto footprintWeight = [&](const SourceTexel& b, double cosAngle, bool coarse) {
        const double gridFactor = coarse ? 20.0 : 40.0;
        const int S =
            std::clamp(int(std::ceil((coarse ? 2.0 : 4.0) * sourceStep / alpha)), 1, coarse ? 32 : 64);
        // Farther than two output texels from t, G_t is smooth over b: a 2 x 2 grid of b suffices.
        const int grid = cosAngle > std::cos(2.0 * (2.0 / n + sourceStep)) ? S : std::min(S, 2);
        double weight = 0.0;
        forEachCell(b.face, b.x, b.y, w, grid, [&](const glm::dvec3& l, double omega) {
            const double angle = std::acos(std::clamp(glm::dot(l, centre), -1.0, 1.0));
            weight += omega * outputTexelWeight(l, angle, gridFactor);
        });
        return weight / texelOmega;
    };
    TexelsParts sum;
    for (const SourceTexel& b : texels) {
        const double cosAngle = glm::dot(centre, b.centre);
        if (cosAngle <= -0.1) continue;
        if (overFootprint) {
            sum.fine.add(footprintWeight(b, cosAngle, false), b.radiance);
            if (withCoarse) sum.coarse.add(footprintWeight(b, cosAngle, true), b.radiance);
        } else if (cosAngle < oneCell) {
            const double weight = cellWeight(centre, b.centre, b.solidAngle, alpha * alpha);
            sum.fine.add(weight, b.radiance);
            sum.coarse.add(weight, b.radiance);
        } else {
            const double angle = std::acos(std::clamp(cosAngle, -1.0, 1.0));
            sum.fine.add(texelWeight(centre, b.face, b.x, b.y, w, alpha, angle, 40.0), b.radiance);
            if (withCoarse)
                sum.coarse.add(texelWeight(centre, b.face, b.x, b.y, w, alpha, angle, 20.0), b.radiance);
        }
    }
    return sum;
}

} // namespace

CubeMap referenceSpecularLevel(const CubeMap& original, int outputFaceSize, float perceptualRoughness) {
    const int w = original.faceSize, n = outputFaceSize;
    const double alpha = std::max(double(perceptualRoughness) * perceptualRoughness, 1e-6);
    // Where the bake averages its bright texels' excess over the output texel, so does the reference; the
    // rest (everything, elsewhere) at the output texel's centre.
    const bool overFootprint = ldFootprintApplies(float(alpha), std::uint32_t(n));
    const FootprintSplit split = overFootprint ? footprintSplit(original) : FootprintSplit{original, {}};
    const CubeMap& source = split.residual;
    const std::size_t faceTexels = std::size_t(w) * w;
    std::vector<glm::dvec3> centres(6 * faceTexels);
    std::vector<double> solidAngles(faceTexels);
    for (int f = 0; f < 6; ++f)
        for (int y = 0; y < w; ++y)
            for (int x = 0; x < w; ++x)
                centres[f * faceTexels + std::size_t(y) * w + x] = texelCentre(f, x, y, w);
    for (int y = 0; y < w; ++y)
        for (int x = 0; x < w; ++x)
            solidAngles[std::size_t(y) * w + x] = texelSolidAngle(x, y, w);
    const double oneCell = oneCellCosine(w, alpha);

    CubeMap out(n);
    tbb::parallel_for(0, 6 * n, [&](int row) {
        int face = row / n, y = row % n;
        for (int x = 0; x < n; ++x) {
            glm::dvec3 nrm =
                glm::normalize(glm::dvec3(cubeFaceDirection(face, (x + 0.5f) / n, (y + 0.5f) / n)));
            glm::dvec3 sum(0.0);
            double weightSum = 0.0; // the whole lobe at the centre: the excess needs no weight of its own
            for (std::size_t k = 0; k < centres.size(); ++k) {
                double cosAngle = glm::dot(nrm, centres[k]);
                if (cosAngle <= -0.1) continue; // entirely below the horizon
                int f = int(k / faceTexels), texel = int(k % faceTexels);
                double weight = 0.0;
                if (cosAngle < oneCell) {
                    weight = cellWeight(nrm, centres[k], solidAngles[std::size_t(texel)], alpha * alpha);
                } else {
                    double angle = std::acos(std::clamp(cosAngle, -1.0, 1.0));
                    weight = texelWeight(nrm, f, texel % w, texel / w, w, alpha, angle);
                }
                sum += weight * glm::dvec3(source.faces[f].pixels[std::size_t(texel)]);
                weightSum += weight;
            }
            sum += texelsParts(w, split.excess, face, x, y, n, alpha, true, false).fine.radiance;
            out.faces[face].at(x, y) = glm::vec4(glm::vec3(sum / weightSum), 1.0f);
        }
    });
    return out;
}

std::uint32_t referenceSamplesPerHalf(std::size_t texelCount) {
    constexpr std::uint64_t kMinPerHalf = 2048, kMaxPerHalf = std::uint64_t(1) << 17;
    constexpr std::uint64_t kPerLevel = kMinPerHalf * 1536;
    const std::uint64_t perTexel = kPerLevel / std::max<std::uint64_t>(texelCount, 1);
    return std::uint32_t(std::clamp(perTexel, kMinPerHalf, kMaxPerHalf));
}

LdTexelReference referenceSpecularTexels(const CubeMap& original, int outputFaceSize,
                                         float perceptualRoughness, std::span<const CubeTexel> texels) {
    const int w = original.faceSize, n = outputFaceSize;
    const double alpha = std::max(double(perceptualRoughness) * perceptualRoughness, 1e-6);
    const double a2 = alpha * alpha;
    const bool overFootprint = ldFootprintApplies(float(alpha), std::uint32_t(n));
    const FootprintSplit split = overFootprint ? footprintSplit(original) : FootprintSplit{original, {}};
    const CubeMap& source = split.residual;
    const std::vector<std::size_t> brightIndices = brightTexels(source);
    const std::vector<SourceTexel> bright = texelList(source, brightIndices);
    // The texels the dim samples read, alpha 0 where bright (integrated above instead): one array and one
    // cache line a sample (the random reads of the source and of a separate flag were ~80% of the time).
    const std::size_t faceTexels = std::size_t(w) * std::size_t(w);
    std::vector<glm::vec4> dimTexels(6 * faceTexels);
    for (std::size_t k = 0; k < dimTexels.size(); ++k)
        dimTexels[k] = glm::vec4(glm::vec3(source.faces[k / faceTexels].pixels[k % faceTexels]), 1.0f);
    for (std::size_t k : brightIndices)
        dimTexels[k].w = 0.0f;
    // GGX sampling of h around the normal: cos theta_h from the CDF variable xi.
    auto cosHalf = [&](double xi) { return std::sqrt((1.0 - xi) / (1.0 + (a2 - 1.0) * xi)); };
    const std::uint32_t samplesPerHalf = referenceSamplesPerHalf(texels.size());
    // The dim rest's samples of h in the normal's frame, two halves under different rotations of the same
    // stratified set: the same for every texel, so computed once (those with NoL > 0 only).
    struct HalfVectorSample {
        double tangent, bitangent, cosTheta; // sin theta_h cos phi, sin theta_h sin phi, cos theta_h
    };
    std::vector<HalfVectorSample> halfSamples[2];
    const glm::dvec2 shifts[2] = {{0.0, 0.0}, {0.61803398875, 0.41421356237}};
    for (int h = 0; h < 2; ++h)
        for (std::uint32_t i = 0; i < samplesPerHalf; ++i) {
            glm::dvec2 u = glm::dvec2((i + 0.5) / samplesPerHalf, double(radicalInverse2(i))) + shifts[h];
            u -= glm::floor(u);
            const double c = cosHalf(u.x), sn = std::sqrt(std::max(0.0, 1.0 - c * c));
            const double phi = 2.0 * kPi * u.y;
            if (2.0 * c * c - 1.0 <= 0.0) continue; // NoL
            halfSamples[h].push_back({sn * std::cos(phi), sn * std::sin(phi), c});
        }
    LdTexelReference out;
    out.value.resize(texels.size());
    out.errorEstimate.resize(texels.size());
    tbb::parallel_for(std::size_t(0), texels.size(), [&](std::size_t k) {
        const CubeTexel& t = texels[k];
        const glm::dvec3 nrm = texelCentre(t.face, t.x, t.y, n);
        // The bright texels exactly at the centre, and the bake's bright excess over the footprint where it
        // averages it, normalized as referenceSpecularLevel: by the lobe's weights at the centre.
        const TexelsParts centre = texelsParts(w, bright, t.face, t.x, t.y, n, alpha, false, true);
        const TexelsParts excess = texelsParts(w, split.excess, t.face, t.x, t.y, n, alpha, true, true);
        const glm::dvec3 fine = centre.fine.radiance + excess.fine.radiance;
        const glm::dvec3 coarse = centre.coarse.radiance + excess.coarse.radiance;
        const double brightWeight = centre.fine.weight;
        // The dim rest: GGX samples of h around the normal, two halves under different rotations.
        const glm::dvec3 up = std::abs(nrm.z) < 0.999 ? glm::dvec3(0, 0, 1) : glm::dvec3(1, 0, 0);
        const glm::dvec3 tx = glm::normalize(glm::cross(up, nrm)), ty = glm::cross(nrm, tx);
        glm::dvec3 half[2] = {glm::dvec3(0.0), glm::dvec3(0.0)};
        double halfWeight[2] = {0.0, 0.0}; // the dim texels' share of the lobe
        for (int h = 0; h < 2; ++h)
            for (const HalfVectorSample& sample : halfSamples[h]) {
                const double c = sample.cosTheta;
                const glm::dvec3 hv = sample.tangent * tx + sample.bitangent * ty + c * nrm;
                const glm::dvec3 l = 2.0 * c * hv - nrm;
                const double NoL = 2.0 * c * c - 1.0;
                const CubeCoord cc = cubeCoordFromDirection(vec3(l));
                const int x = std::clamp(int(cc.s * float(w)), 0, w - 1),
                          y = std::clamp(int(cc.t * float(w)), 0, w - 1);
                const std::size_t index = (std::size_t(cc.face) * w + y) * w + x;
                const glm::vec4& texel = dimTexels[index];
                if (texel.w == 0.0f) continue;
                half[h] += glm::dvec3(texel) * (4.0 * NoL / samplesPerHalf);
                halfWeight[h] += 4.0 * NoL / samplesPerHalf;
            }
        // The integral of pi D NoL (the weights' measure) over the sphere, bright part exact, dim sampled.
        const double lobe = brightWeight + kPi * 0.5 * (halfWeight[0] + halfWeight[1]);
        const glm::dvec3 value = (fine + kPi * 0.5 * (half[0] + half[1])) / lobe;
        out.value[k] = value;
        // Each half's own estimate (self-normalized), and the bright weights at half the grid.
        const glm::dvec3 first = (fine + kPi * half[0]) / (brightWeight + kPi * halfWeight[0]);
        const glm::dvec3 second = (fine + kPi * half[1]) / (brightWeight + kPi * halfWeight[1]);
        out.errorEstimate[k] = 0.5 * glm::abs(first - second) + glm::abs(fine - coarse) / lobe;
    });
    return out;
}

} // namespace ibl
