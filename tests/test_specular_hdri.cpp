// The specular chain on the real HDR environments of ../shared/data/hdri (skipped when absent):
// accuracy against the brute-force reference, bounds, and seams.
#include <iblbake/baker/ingest.h>
#include <iblbake/baker/specular.h>

#include <cube.h>

#include "test_support.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <sstream>

namespace fs = std::filesystem;

namespace {

using namespace ibl;
using namespace ibl::test;

float luminance(const glm::vec4& p) {
    return 0.2126f * p.x + 0.7152f * p.y + 0.0722f * p.z;
}

// Mean difference between texels that share a face edge, over the mean difference between neighbours
// inside faces (levels of at least 4 texels, where faces have an interior). A difference is relative,
// |La - Lb| / (La + Lb) of luminance, so that a sun crossing an edge or lying inside a face does not
// decide the ratio by itself.
double seamRatio(const CubeMap& level) {
    const int n = level.faceSize;
    double edge = 0.0, interior = 0.0;
    long edgeCount = 0, interiorCount = 0;
    for (int f = 0; f < 6; ++f)
        for (int y = 0; y < n; ++y)
            for (int x = 0; x < n; ++x) {
                float here = luminance(level.faces[f].at(x, y));
                auto difference = [&](const glm::vec4& other) {
                    float l = luminance(other);
                    return std::abs(here - l) / std::max(here + l, 1e-12f);
                };
                const int dx[4] = {1, -1, 0, 0}, dy[4] = {0, 0, 1, -1};
                for (int k = 0; k < 4; ++k) {
                    int nx = x + dx[k], ny = y + dy[k];
                    if (nx >= 0 && nx < n && ny >= 0 && ny < n) {
                        interior += difference(level.faces[f].at(nx, ny));
                        ++interiorCount;
                    } else {
                        CubeCoord c =
                            cubeCoordFromDirection(cubeFaceDirection(f, (nx + 0.5f) / n, (ny + 0.5f) / n));
                        int sx = std::clamp(int(c.s * n), 0, n - 1), sy = std::clamp(int(c.t * n), 0, n - 1);
                        edge += difference(level.faces[c.face].at(sx, sy));
                        ++edgeCount;
                    }
                }
            }
    return (edge / edgeCount) / (interior / interiorCount);
}

class RealHdri : public SharedHdriTest {};

// Relative mean absolute error per level against the brute force, at 32-texel faces (where the fp64
// reference over every texel is affordable); production must stay within 2% on every level.
TEST_P(RealHdri, ProductionWithin2PercentOfBruteForcePerLevel) {
    CubeMap source = loadSharedHdri(GetParam(), 32);
    const int levelCount = levelCountFor(32, SpecularSettings{});
    std::vector<CubeMap> references;
    for (int m = 1; m < levelCount; ++m)
        references.push_back(referenceSpecularLevel(
            source, 32 >> m, perceptualRoughnessForLevel(m, levelCount, MipMapping::Frostbite)));
    for (Quality quality : {Quality::Draft, Quality::Production, Quality::Reference}) {
        SpecularSettings settings;
        settings.quality = quality;
        CubeMapChain chain = bakeSpecular(source, settings, openclOrCpu());
        std::printf("%-26s %-10s", GetParam(), qualityName(quality));
        for (int m = 1; m < levelCount; ++m) {
            double error = relativeMeanAbsError(chain.levels[std::size_t(m)], references[std::size_t(m - 1)]);
            std::printf(" L%d %.4f", m, error);
            if (quality != Quality::Draft) {
                EXPECT_LT(error, 0.02) << GetParam() << " level " << m;
            }
        }
        std::printf("\n");
    }
}

TEST_P(RealHdri, FiniteBoundedAndSeamless) {
    IngestSettings ingest;
    ingest.sourceFaceSize = 64;
    SourceEnvironment env = ingestEnvironment({hdriPath(GetParam())}, ingest);
    float brightest = 0.0f;
    for (const ImageRGBA& face : env.cube.faces)
        for (const glm::vec4& p : face.pixels)
            brightest = std::max({brightest, p.x, p.y, p.z});
    CubeMapChain chain = bakeSpecular(env.cube, SpecularSettings{}, openclOrCpu());
    // Level 0 is the source itself: its ratio is the content's (studio_small_03's white floor ends
    // almost exactly on the -Y face's edges, 1.57). Filtering must add no seam of its own: every level
    // stays within 1.5, or within 10% of what the content already has.
    const double contentRatio = seamRatio(chain.levels[0]);
    std::printf("%-26s seam ratio", GetParam());
    for (std::size_t m = 0; m < chain.levels.size(); ++m) {
        for (const ImageRGBA& face : chain.levels[m].faces)
            for (const glm::vec4& p : face.pixels)
                for (int c = 0; c < 3; ++c) {
                    ASSERT_TRUE(std::isfinite(p[c])) << "level " << m;
                    ASSERT_GE(p[c], 0.0f);
                    ASSERT_LE(p[c], brightest * (1.0f + 1e-5f)) << "level " << m;
                }
        // The brightest input pixel bounds every output texel (luminance of the source too).
        for (const ImageRGBA& face : chain.levels[m].faces)
            for (const glm::vec4& p : face.pixels)
                ASSERT_LE(luminance(p), env.report.maxLuminanceIn * 1.0001f);
        if (chain.levels[m].faceSize >= 4) {
            double ratio = seamRatio(chain.levels[m]);
            std::printf(" L%zu %.2f", m, ratio);
            EXPECT_LE(ratio, std::max(1.5, 1.1 * contentRatio)) << "level " << m;
        }
    }
    std::printf("\n");
}

// The glossy highlight at production (256-px faces): at every level with faces of 4 px or more, the texels
// within three texel widths of the map's brightest texel (its sun, on sun maps) against the reference
// (referenceSpecularTexels, which averages the bright excess over each texel's footprint where the bake
// does): their energy (sum of luminance x solid angle) within 2% and their relative mean error within 5%,
// with the reference's own estimate printed (issue 14, "Must show").
TEST_P(RealHdri, SunNeighbourhoodAtProduction) {
    const int size = 256;
    const CubeMap source = loadSharedHdri(GetParam(), size);
    glm::vec3 sun(0.0f);
    float brightest = -1.0f;
    for (int f = 0; f < 6; ++f)
        for (int y = 0; y < size; ++y)
            for (int x = 0; x < size; ++x)
                if (const float l = luminance(source.faces[f].at(x, y)); l > brightest)
                    brightest = l, sun = cubeTexelDirection(f, std::uint32_t(x), std::uint32_t(y), size);
    const CubeMapChain chain = bakeSpecular(source, SpecularSettings{}, openclOrCpu());
    const int levelCount = int(chain.levels.size());
    std::printf("%-26s sun neighbourhood, energy ratio / relative mean error / reference estimate:",
                GetParam());
    for (int m = 1; m < levelCount && (size >> m) >= 4; ++m) {
        const int n = size >> m;
        const CubeMap& level = chain.levels[std::size_t(m)];
        std::vector<CubeTexel> texels;
        for (int f = 0; f < 6; ++f)
            for (int y = 0; y < n; ++y)
                for (int x = 0; x < n; ++x)
                    if (glm::dot(cubeTexelDirection(f, std::uint32_t(x), std::uint32_t(y), std::uint32_t(n)),
                                 sun) > std::cos(3.0f * 2.0f / float(n)))
                        texels.push_back({f, x, y});
        const LdTexelReference reference = referenceSpecularTexels(
            source, n, perceptualRoughnessForLevel(m, levelCount, MipMapping::Frostbite), texels);
        double bakeEnergy = 0.0, referenceEnergy = 0.0, difference = 0.0, sum = 0.0, estimate = 0.0;
        for (std::size_t k = 0; k < texels.size(); ++k) {
            const CubeTexel& t = texels[k];
            const double omega = cubeTexelSolidAngle(t.x, t.y, n);
            const glm::vec4 baked = level.faces[t.face].at(t.x, t.y);
            const glm::dvec3 want = reference.value[k];
            bakeEnergy += luminance(baked) * omega;
            referenceEnergy += (0.2126 * want.x + 0.7152 * want.y + 0.0722 * want.z) * omega;
            for (int c = 0; c < 3; ++c)
                difference += std::abs(double(baked[c]) - want[c]), sum += want[c],
                    estimate += reference.errorEstimate[k][c];
        }
        std::printf(" L%d %.4f/%.4f/%.4f", m, bakeEnergy / referenceEnergy, difference / sum, estimate / sum);
        EXPECT_NEAR(bakeEnergy / referenceEnergy, 1.0, 0.02) << GetParam() << " level " << m;
        EXPECT_LT(difference / sum, 0.05) << GetParam() << " level " << m;
    }
    std::printf("\n");
}

INSTANTIATE_TEST_SUITE_P(SharedHdris, RealHdri, ::testing::ValuesIn(kSharedHdris), hdriTestName);

} // namespace
