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
#include <cmath>
#include <span>

namespace ibl {

namespace {

glm::dvec3 texelCentre(int face, int x, int y, int w) {
    return glm::normalize(glm::dvec3(cubeFaceDirection(face, (x + 0.5f) / w, (y + 0.5f) / w)));
}

// The LD weight of one source texel of constant radiance for the lobe around `nrm` (N = V = R): the
// integral of pi D(h) NoL over the texel (Listing 19's estimator's expectation, up to normalization),
// on an S x S grid of exact sub-texel solid angles. S grows as the lobe gets narrow compared with the
// texel and the texel near the lobe: D's relative change across a sub-texel is about 4 (size /
// max(angle, alpha)), kept under ~0.1 (gridFactor 40; the accuracy check halves it).
double texelWeight(const glm::dvec3& nrm, int f, int x, int y, int w, double alpha, double angle,
                   double gridFactor = 40.0) {
    const double a2 = alpha * alpha;
    const double texelAngle = std::sqrt(4.0 * kPi / (6.0 * double(w) * w)); // typical, in radians
    const float texelSize = 2.0f / float(w);
    // Within three texels of a lobe under a quarter texel wide, D is too peaked for any grid: the
    // closed-form small-angle integral (kernels/ld.h, checked against quadrature in tests) is exact
    // to O(texel angle^2).
    // narrowLobeTexelWeight integrates D NoL, the grid below pi D NoL (a^2 / d^2 NoL): the same measure.
    if (narrowLobeClosedFormApplies(float(alpha), texelSize, float(angle)))
        return kPi * double(narrowLobeTexelWeight(frameFromNormal(vec3(nrm)), f, -1.0f + x * texelSize,
                                                  -1.0f + y * texelSize, texelSize, float(alpha)));
    int S = int(std::clamp(std::ceil(gridFactor * texelAngle / std::max(angle, alpha)), 1.0, 256.0));
    double weight = 0.0, step = 2.0 / (double(w) * S);
    for (int j = 0; j < S; ++j)
        for (int i = 0; i < S; ++i) {
            double u0 = -1.0 + (x * S + i) * step, v0 = -1.0 + (y * S + j) * step;
            double omega = cubeRectangleSolidAngleF64(u0, v0, u0 + step, v0 + step);
            if (S == 1) omega = cubeTexelSolidAngle(x, y, w);
            float s = float((x * S + i + 0.5) / (double(w) * S)),
                  t = float((y * S + j + 0.5) / (double(w) * S));
            glm::dvec3 l = glm::normalize(glm::dvec3(cubeFaceDirection(f, s, t)));
            double NoL = glm::dot(nrm, l);
            if (NoL <= 0.0) continue;
            double NoH = glm::dot(nrm, glm::normalize(nrm + l));
            double d = NoH * NoH * (a2 - 1.0) + 1.0;
            weight += a2 / (d * d) * NoL * std::abs(omega);
        }
    return weight;
}

// A source texel and its radiance, as the references integrate it exactly.
struct SourceTexel {
    int face, x, y;
    glm::dvec3 radiance;
};

std::vector<SourceTexel> texelList(const CubeMap& source, std::span<const std::size_t> indices) {
    const std::size_t w = std::size_t(source.faceSize);
    std::vector<SourceTexel> out;
    for (std::size_t k : indices)
        out.push_back({int(k / (w * w)), int(k % w), int(k % (w * w) / w),
                       glm::dvec3(source.faces[k / (w * w)].pixels[k % (w * w)])});
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
        out.excess.push_back({int(e[7]), int(e[8]), int(e[9]), glm::dvec3(e[4], e[5], e[6])});
    }
    return out;
}

// The part of output texel (face, x, y) of an n-texel level that `texels` (of a w-texel source) give: the
// sums of radiance x weight and of the weights, at the texel's centre, or with `overFootprint` averaged over
// the texel. The footprint mean of a texel b is integral_b G_t(l) dl / Omega_t with G_t(l) = integral_t
// pi D NoL dn (the kernel is symmetric in n and l): texelWeight with the output texel as "the texel" around
// l, on an S x S grid of b, S = 4 source texel / alpha up to 64 (G_t changes over about alpha at t's
// edges), 2 x 2 beyond two texels. `coarse` halves the grids (the error estimate: where a grid does not
// resolve alpha the rule converges only linearly, so the estimate is the whole difference).
struct TexelsPart {
    glm::dvec3 radiance{0.0};
    double weight = 0.0;
};

TexelsPart texelsPart(int w, std::span<const SourceTexel> texels, int face, int x, int y, int n, double alpha,
                      bool overFootprint, bool coarse) {
    const double gridFactor = coarse ? 20.0 : 40.0;
    const glm::dvec3 centre = texelCentre(face, x, y, n);
    const double sourceStep = 2.0 / w;
    const int S = std::clamp(int(std::ceil((coarse ? 2.0 : 4.0) * sourceStep / alpha)), 1, coarse ? 32 : 64);
    auto patch = [](double u, double v, double size) {
        return std::abs(cubeRectangleSolidAngleF64(u, v, u + size, v + size));
    };
    const double texelOmega = patch(-1.0 + 2.0 * x / n, -1.0 + 2.0 * y / n, 2.0 / n);
    TexelsPart sum;
    for (const SourceTexel& b : texels) {
        const double cosAngle = glm::dot(centre, texelCentre(b.face, b.x, b.y, w));
        if (cosAngle <= -0.1) continue;
        double weight = 0.0;
        if (!overFootprint) {
            const double angle = std::acos(std::clamp(cosAngle, -1.0, 1.0));
            weight = texelWeight(centre, b.face, b.x, b.y, w, alpha, angle, gridFactor);
        } else {
            // Farther than two output texels from t, G_t is smooth over b: a 2 x 2 grid of b suffices.
            const int grid = cosAngle > std::cos(2.0 * (2.0 / n + sourceStep)) ? S : std::min(S, 2);
            const double step = sourceStep / grid;
            for (int j = 0; j < grid; ++j)
                for (int i = 0; i < grid; ++i) {
                    const double u = -1.0 + b.x * sourceStep + i * step,
                                 v = -1.0 + b.y * sourceStep + j * step;
                    const glm::dvec3 l = glm::normalize(glm::dvec3(cubeFaceDirection(
                        b.face, float(0.5 * (u + 0.5 * step + 1.0)), float(0.5 * (v + 0.5 * step + 1.0)))));
                    const double angle = std::acos(std::clamp(glm::dot(l, centre), -1.0, 1.0));
                    weight += patch(u, v, step) * texelWeight(l, face, x, y, n, alpha, angle, gridFactor);
                }
            weight /= texelOmega;
        }
        sum.radiance += weight * b.radiance;
        sum.weight += weight;
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
    for (int f = 0; f < 6; ++f)
        for (int y = 0; y < w; ++y)
            for (int x = 0; x < w; ++x)
                centres[f * faceTexels + std::size_t(y) * w + x] = texelCentre(f, x, y, w);

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
                double angle = std::acos(std::clamp(cosAngle, -1.0, 1.0));
                int f = int(k / faceTexels), texel = int(k % faceTexels);
                double weight = texelWeight(nrm, f, texel % w, texel / w, w, alpha, angle);
                sum += weight * glm::dvec3(source.faces[f].pixels[std::size_t(texel)]);
                weightSum += weight;
            }
            sum += texelsPart(w, split.excess, face, x, y, n, alpha, true, false).radiance;
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
    std::vector<char> isBright(6 * std::size_t(w) * w, 0);
    for (std::size_t k : brightIndices)
        isBright[k] = 1;
    // GGX sampling of h around the normal: cos theta_h from the CDF variable xi.
    auto cosHalf = [&](double xi) { return std::sqrt((1.0 - xi) / (1.0 + (a2 - 1.0) * xi)); };
    const std::uint32_t samplesPerHalf = referenceSamplesPerHalf(texels.size());
    LdTexelReference out;
    out.value.resize(texels.size());
    out.errorEstimate.resize(texels.size());
    tbb::parallel_for(std::size_t(0), texels.size(), [&](std::size_t k) {
        const CubeTexel& t = texels[k];
        const glm::dvec3 nrm = texelCentre(t.face, t.x, t.y, n);
        // The bright texels exactly at the centre, and the bake's bright excess over the footprint where it
        // averages it, normalized as referenceSpecularLevel: by the lobe's weights at the centre.
        const TexelsPart centre = texelsPart(w, bright, t.face, t.x, t.y, n, alpha, false, false);
        const glm::dvec3 excess =
            texelsPart(w, split.excess, t.face, t.x, t.y, n, alpha, true, false).radiance;
        const glm::dvec3 fine = centre.radiance + excess;
        const glm::dvec3 coarse =
            texelsPart(w, bright, t.face, t.x, t.y, n, alpha, false, true).radiance +
            texelsPart(w, split.excess, t.face, t.x, t.y, n, alpha, true, true).radiance;
        const double brightWeight = centre.weight;
        // The dim rest: GGX samples of h around the normal, two halves under different rotations.
        const glm::dvec3 up = std::abs(nrm.z) < 0.999 ? glm::dvec3(0, 0, 1) : glm::dvec3(1, 0, 0);
        const glm::dvec3 tx = glm::normalize(glm::cross(up, nrm)), ty = glm::cross(nrm, tx);
        glm::dvec3 half[2] = {glm::dvec3(0.0), glm::dvec3(0.0)};
        double halfWeight[2] = {0.0, 0.0}; // the dim texels' share of the lobe
        const glm::dvec2 shifts[2] = {{0.0, 0.0}, {0.61803398875, 0.41421356237}};
        for (int h = 0; h < 2; ++h)
            for (std::uint32_t i = 0; i < samplesPerHalf; ++i) {
                glm::dvec2 u = glm::dvec2((i + 0.5) / samplesPerHalf, double(radicalInverse2(i))) + shifts[h];
                u -= glm::floor(u);
                const double c = cosHalf(u.x), sn = std::sqrt(std::max(0.0, 1.0 - c * c));
                const double phi = 2.0 * kPi * u.y;
                const glm::dvec3 hv = sn * std::cos(phi) * tx + sn * std::sin(phi) * ty + c * nrm;
                const glm::dvec3 l = 2.0 * c * hv - nrm;
                const double NoL = 2.0 * c * c - 1.0;
                if (NoL <= 0.0) continue;
                const CubeCoord cc = cubeCoordFromDirection(vec3(l));
                const int x = std::clamp(int(cc.s * float(w)), 0, w - 1),
                          y = std::clamp(int(cc.t * float(w)), 0, w - 1);
                const std::size_t index = (std::size_t(cc.face) * w + y) * w + x;
                if (isBright[index]) continue;
                half[h] += glm::dvec3(source.faces[cc.face].at(x, y)) * (4.0 * NoL / samplesPerHalf);
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
