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

INSTANTIATE_TEST_SUITE_P(SharedHdris, RealHdri, ::testing::ValuesIn(kSharedHdris), hdriTestName);

} // namespace
