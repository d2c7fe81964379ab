// Hard cases where a cube's seams and sizes meet a bright source (checklist in test_hard_cases.cpp): a small
// sun exactly on a cube edge and on a corner, and a map that is one bright texel at every face size. With
// N = V = R the pre-filter's kernel depends only on the angle between two directions, so a level's energy
// (sum of radiance x texel solid angle) would equal its source's if each texel held its footprint's mean;
// where several faces share the source, their shares follow the symmetry. Where the lobe is narrower than a
// texel the bake stores that footprint mean for the bright texels (kernels/ld.h ldFootprintApplies), so
// every level but the 1 x 1 one keeps its source's energy: measured at 64 px before / after, edge L2 0.503 /
// 1.001 and corner L1 1.359 / 1.000; a sun swept across one texel moved L2 by 61% before, by 0.01% after.
// The 1 x 1 level (0.95-1.16 here) is the coarse-level question of issue 14, item 2.
#include <iblbake/baker/specular.h>

#include <cube.h>

#include "test_support.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace {

using namespace ibl;
using namespace ibl::test;

constexpr double kSunRadius = 0.0047; // radians: the real sun's 0.27 degrees
constexpr float kSky = 1.0f;
constexpr float kSunRadiance = 1e5f;

// A uniform sky with a disk sun toward `sun`, each texel holding its exact coverage (16 x 16 points).
CubeMap skyWithSun(int n, glm::dvec3 sun) {
    CubeMap cube = makeCube(n, [](glm::dvec3) { return glm::vec3(kSky); });
    const double cosMargin = std::cos(kSunRadius + 4.0 / n);
    for (int f = 0; f < 6; ++f)
        for (int y = 0; y < n; ++y)
            for (int x = 0; x < n; ++x) {
                if (glm::dot(texelCentre(f, x, y, n), sun) < cosMargin) continue;
                int inside = 0;
                for (int j = 0; j < 16; ++j)
                    for (int i = 0; i < 16; ++i) {
                        glm::dvec3 d = glm::normalize(glm::dvec3(cubeFaceDirection(
                            f, (x + (i + 0.5f) / 16.0f) / n, (y + (j + 0.5f) / 16.0f) / n)));
                        inside += glm::dot(d, sun) >= std::cos(kSunRadius);
                    }
                cube.faces[f].at(x, y) += glm::vec4(glm::vec3(kSunRadiance * inside / 256.0f), 0.0f);
            }
    return cube;
}

// sum over one face's texels of (L - background) x solid angle.
double faceEnergy(const CubeMap& level, int f, float background) {
    double sum = 0.0;
    const int n = level.faceSize;
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x)
            sum += (double(level.faces[f].at(x, y).g) - background) * double(cubeTexelSolidAngle(x, y, n));
    return sum;
}

double energy(const CubeMap& level, float background) {
    double sum = 0.0;
    for (int f = 0; f < 6; ++f)
        sum += faceEnergy(level, f, background);
    return sum;
}

// Finite, non-negative, and symmetric: the faces that share an edge or corner sun receive equal shares of
// every level's energy (within 1%), and every level with faces of 2 px or more keeps the source's energy
// within 1%.
TEST(HardCases, SunOnACubeEdgeAndCornerStaysSymmetric) {
    const int n = 64;
    struct Case {
        const char* name;
        glm::dvec3 sun;
        std::vector<int> faces; // that share it equally (+X, -X, +Y, -Y, +Z, -Z = 0..5)
    };
    const Case cases[] = {{"edge +X/+Y", glm::normalize(glm::dvec3(1, 1, 0)), {0, 2}},
                          {"corner +X/+Y/+Z", glm::normalize(glm::dvec3(1, 1, 1)), {0, 2, 4}}};
    for (Executor executor : {Executor::cpu(), openclOrCpu()})
        for (const Case& c : cases) {
            SCOPED_TRACE(c.name);
            const CubeMapChain chain = bakeSpecular(skyWithSun(n, c.sun), SpecularSettings{}, executor);
            const double source = energy(chain.levels[0], kSky);
            std::printf("%s (%s), energy / source:", c.name, backendName(executor.backend()));
            for (std::size_t m = 1; m < chain.levels.size(); ++m) {
                const CubeMap& level = chain.levels[m];
                expectFiniteNonNegative(level, ("level " + std::to_string(m)).c_str());
                double low = 1e300, high = -1e300;
                for (int f : c.faces) {
                    low = std::min(low, faceEnergy(level, f, kSky));
                    high = std::max(high, faceEnergy(level, f, kSky));
                }
                EXPECT_LT(high / low - 1.0, 0.01) << "level " << m;
                if (level.faceSize >= 2) {
                    EXPECT_NEAR(energy(level, kSky) / source, 1.0, 0.01) << "level " << m;
                }
                std::printf(" L%zu %.3f", m, energy(level, kSky) / source);
            }
            std::printf("\n");
        }
}

// A sun moving by sub-texel steps (a map rotated by 1/8 of a texel at a time, across one whole texel, and
// past a cube edge): each level with faces of 2 px or more keeps its source's sun energy within 1% at every
// step, so a rotating map does not pulse (the 1 x 1 level is printed).
TEST(HardCases, RotationSweepKeepsEachLevelsSunEnergy) {
    const int n = 64;
    const double texelAngle = 2.0 / n; // radians at a face centre
    for (Executor executor : {Executor::cpu(), openclOrCpu()}) {
        for (double start : {0.3, 0.7853981633974483 - 4.0 * texelAngle / 8.0}) { // mid-face; across +X/+Z
            std::vector<std::vector<double>> ratios;                              // [step][level]
            for (int step = 0; step <= 8; ++step) {
                const double azimuth = start + step * texelAngle / 8.0, elevation = 0.2;
                const glm::dvec3 sun(std::sin(azimuth) * std::cos(elevation), std::sin(elevation),
                                     std::cos(azimuth) * std::cos(elevation));
                const CubeMapChain chain = bakeSpecular(skyWithSun(n, sun), SpecularSettings{}, executor);
                const double source = energy(chain.levels[0], kSky);
                ratios.emplace_back();
                for (std::size_t m = 1; m < chain.levels.size(); ++m)
                    ratios.back().push_back(energy(chain.levels[m], kSky) / source);
            }
            std::printf("rotation sweep from %.3f rad (%s), level energy / source, min..max over 9 steps:",
                        start, backendName(executor.backend()));
            for (std::size_t m = 0; m < ratios[0].size(); ++m) {
                double low = 1e300, high = -1e300;
                for (const auto& step : ratios)
                    low = std::min(low, step[m]), high = std::max(high, step[m]);
                std::printf(" L%zu %.4f..%.4f", m + 1, low, high);
                if ((n >> (m + 1)) < 2) continue;
                EXPECT_LT(high / low - 1.0, 0.01) << "level " << m + 1 << " from " << start;
                EXPECT_NEAR(low, 1.0, 0.01) << "level " << m + 1 << " from " << start;
                EXPECT_NEAR(high, 1.0, 0.01) << "level " << m + 1 << " from " << start;
            }
            std::printf("\n");
        }
    }
}

// One bright texel on a black map at every face size from 1 to 256: every level finite and non-negative
// (4 px faces gave NaN where the narrow-lobe closed form met corners behind the lobe's tangent plane), each
// level's brightest texel the one holding the bright texel or a neighbour of it (a footprint mean: a bright
// texel on the edge of a large texel may light its smaller neighbour more), and every level with faces of
// 4 px or more keeping the source's energy within 2%.
TEST(HardCases, OneBrightTexelAtEveryFaceSize) {
    for (int n = 1; n <= 256; n *= 2) {
        SCOPED_TRACE("face size " + std::to_string(n));
        CubeMap cube = makeCube(n, [](glm::dvec3) { return glm::vec3(0.0f); });
        const int bx = n / 3, by = n / 4;
        cube.faces[4].at(bx, by) = glm::vec4(1e4f, 1e4f, 1e4f, 1.0f);
        for (Executor executor : {Executor::cpu(), openclOrCpu()}) {
            const CubeMapChain chain = bakeSpecular(cube, SpecularSettings{}, executor);
            ASSERT_EQ(int(chain.levels.size()), mipLevelCount(n));
            const double source = energy(chain.levels[0], 0.0f);
            std::printf("n %d (%s), energy / source:", n, backendName(executor.backend()));
            for (std::size_t m = 1; m < chain.levels.size(); ++m) {
                const CubeMap& level = chain.levels[m];
                expectFiniteNonNegative(level, ("level " + std::to_string(m)).c_str());
                const int size = level.faceSize;
                double brightest = -1.0;
                glm::ivec3 brightestAt(0);
                for (int f = 0; f < 6; ++f)
                    for (int y = 0; y < size; ++y)
                        for (int x = 0; x < size; ++x)
                            if (const double value = level.faces[f].at(x, y).g; value > brightest)
                                brightest = value, brightestAt = {f, x, y};
                const int scale = n / size; // source texels per level texel
                EXPECT_EQ(brightestAt.x, 4) << "level " << m;
                EXPECT_LE(std::abs(brightestAt.y - bx / scale), 1) << "level " << m;
                EXPECT_LE(std::abs(brightestAt.z - by / scale), 1) << "level " << m;
                if (size >= 4) {
                    EXPECT_NEAR(energy(level, 0.0f) / source, 1.0, 0.02) << "level " << m;
                }
                std::printf(" L%zu %.3f", m, energy(level, 0.0f) / source);
            }
            std::printf("\n");
        }
    }
}

} // namespace
