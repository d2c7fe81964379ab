// Photometric statistics (environment_stats.h), calibration factors (calibration.h) and the `inspect` and
// `calibrate` commands end to end.
//
// Tolerances: exact geometry sums (4 pi, pi, zero vector) to 1e-9 relative (double accumulation of ~1e5
// terms); constant environments to 1e-6 (float pixels); factors for --scale/--ev100/--radiometric exact
// (the output pixel is the input pixel times float(factor), bit for bit); round trips through a file and
// `inspect` to 0.5 % (the figure; they agree to ~1e-6, float storage being the only loss).
#include "iblbake/baker/calibration.h"
#include "iblbake/baker/environment_stats.h"
#include "iblbake/baker/ingest.h"
#include "iblbake/baker/sun.h"
#include "iblbake/core/error.h"

#include "cli_runner.h"

#include <cube.h>

#include "sphere_texels_support.h"
#include <OpenImageIO/imageio.h>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <tbb/global_control.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <numbers>
#include <random>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;
using namespace ibl;
using ibl::test::CliRun;
using ibl::test::cubeOf;
using ibl::test::freshTempDir;
using ibl::test::latLongOf;
using ibl::test::lineCount;
using ibl::test::runCli;

constexpr double kPi = std::numbers::pi;

// ---------------------------------------------------------------------------------------------------
// Geometry and statistics

void expectExactGeometry(const SphereTexels& t) {
    double omega = 0.0, up = 0.0;
    glm::dvec3 vec(0.0);
    for (std::size_t i = 0; i < t.size(); ++i) {
        const double w = t.solidAngle(i);
        ASSERT_GT(w, 0.0) << i;
        const glm::dvec3 v = t.vectorSolidAngle(i);
        ASSERT_LE(glm::length(v), w * (1.0 + 1e-12)) << i;
        ASSERT_GE(t.upwardCosine(i), 0.0);
        ASSERT_LE(t.upwardCosine(i), w * (1.0 + 1e-12));
        omega += w;
        up += t.upwardCosine(i);
        vec += v;
    }
    EXPECT_NEAR(omega, 4.0 * kPi, 1e-9 * 4.0 * kPi);
    EXPECT_NEAR(up, kPi, 1e-9 * kPi);
    EXPECT_LT(glm::length(vec), 1e-9);
}

TEST(EnvironmentGeometry, CubeTexelsAreExact) {
    for (int n : {1, 2, 7, 16, 33}) { // odd sizes: side-face rows straddle the horizon
        SCOPED_TRACE(n);
        const CubeMap cube(n);
        expectExactGeometry(SphereTexels(cube));
    }
    // Same solid angles as kernels/cube.h (float there).
    const CubeMap cube(64);
    const SphereTexels t(cube);
    for (int j = 0; j < 64; j += 9)
        for (int i = 0; i < 64; i += 7)
            EXPECT_NEAR(t.solidAngle(std::size_t(j) * 64 + i), cubeTexelSolidAngle(i, j, 64),
                        2e-4 * t.solidAngle(std::size_t(j) * 64 + i));
}

// The cube geometry is read from a table of one face quadrant (mirrored, and turned into each face's frame):
// it must equal every face's own texel integrals. The reference integrates on each face plane, where
// d omega = da db / (1 + a^2 + b^2)^(3/2) and the direction is (o + a u + b v) / sqrt(1 + a^2 + b^2), by
// 3-point Gauss-Legendre on 4 x 4 cells per texel (smooth integrands: ~1e-10 here); the upward cosine
// over the part above the horizon (side faces: b <= 0, as y = -b). A wrong mirror or frame is off by ~1.
TEST(EnvironmentGeometry, CubeTableMatchesEachFacesIntegrals) {
    const double nodes[3] = {-std::sqrt(0.6), 0.0, std::sqrt(0.6)},
                 weights[3] = {5.0 / 9.0, 8.0 / 9.0, 5.0 / 9.0};
    struct Integrals {
        double omega = 0.0, upward = 0.0;
        glm::dvec3 vector{0.0};
    };
    for (int n : {5, 8, 34}) {
        const CubeMap cube(n);
        const SphereTexels texels(cube);
        double worst = 0.0;
        for (int face = 0; face < 6; ++face) {
            const glm::dvec3 o(cubeFaceDirection(face, 0.5f, 0.5f));
            const glm::dvec3 u = glm::dvec3(cubeFaceDirection(face, 1.0f, 0.5f)) - o,
                             v = glm::dvec3(cubeFaceDirection(face, 0.5f, 1.0f)) - o;
            const auto integrate = [&](double a0, double a1, double b0, double b1, Integrals& sum,
                                       bool upward) {
                constexpr int kCells = 4;
                const double da = (a1 - a0) / kCells, db = (b1 - b0) / kCells;
                for (int ca = 0; ca < kCells; ++ca)
                    for (int cb = 0; cb < kCells; ++cb)
                        for (int p = 0; p < 3; ++p)
                            for (int q = 0; q < 3; ++q) {
                                const double a = a0 + da * (ca + 0.5 + 0.5 * nodes[p]);
                                const double b = b0 + db * (cb + 0.5 + 0.5 * nodes[q]);
                                const double r2 = 1.0 + a * a + b * b;
                                const double w =
                                    weights[p] * weights[q] * 0.25 * da * db / (r2 * std::sqrt(r2));
                                const glm::dvec3 d = (o + a * u + b * v) / std::sqrt(r2);
                                if (upward) {
                                    sum.upward += w * std::max(0.0, d.y);
                                } else {
                                    sum.omega += w;
                                    sum.vector += w * d;
                                }
                            }
            };
            for (int j = 0; j < n; ++j)
                for (int i = 0; i < n; ++i) {
                    const double step = 2.0 / n;
                    const double a0 = -1.0 + i * step, a1 = a0 + step, b0 = -1.0 + j * step, b1 = b0 + step;
                    Integrals ref;
                    integrate(a0, a1, b0, b1, ref, false);
                    if (face == 2) integrate(a0, a1, b0, b1, ref, true);
                    if (face != 2 && face != 3 && b0 < 0.0)
                        integrate(a0, a1, b0, std::min(b1, 0.0), ref, true);
                    const std::size_t k = (std::size_t(face) * n + j) * n + i;
                    worst = std::max({worst, std::fabs(texels.solidAngle(k) - ref.omega) / ref.omega,
                                      glm::length(texels.vectorSolidAngle(k) - ref.vector) / ref.omega,
                                      std::fabs(texels.upwardCosine(k) - ref.upward) / ref.omega});
                }
        }
        EXPECT_LT(worst, 1e-6) << "face size " << n;
    }
}

TEST(EnvironmentGeometry, LatLongPixelsAreExact) {
    for (auto [w, h] : {std::pair{4, 2}, {64, 32}, {63, 31}, {100, 50}}) {
        SCOPED_TRACE(std::to_string(w) + "x" + std::to_string(h));
        const ImageRGBA im(w, h);
        for (LatLongPixels placement : {LatLongPixels::Centre, LatLongPixels::OpenExr})
            expectExactGeometry(SphereTexels(im, placement));
    }
    // Pixel (x, y) looks along the docs/conventions.md direction of its centre in the placement's grid (pixel
    // centres (x+0.5)/W; OpenEXR's x/(W-1)), except at the poles where its cell's centroid is off the pole.
    const ImageRGBA im(64, 32);
    const SphereTexels centre(im, LatLongPixels::Centre), openExr(im, LatLongPixels::OpenExr);
    EXPECT_GT(
        glm::dot(centre.direction(12 * 64 + 10), glm::dvec3(directionFromLatlong(10.5f / 64, 12.5f / 32))),
        std::cos(0.001));
    EXPECT_GT(
        glm::dot(openExr.direction(12 * 64 + 10), glm::dvec3(directionFromLatlong(10.0f / 63, 12.0f / 31))),
        std::cos(0.001));
    EXPECT_FALSE(centre.sameGridAs(openExr));
    EXPECT_THROW(SphereTexels(ImageRGBA(1, 1), LatLongPixels::Centre), Error);
    EXPECT_THROW(SphereTexels(im, LatLongPixels::Auto), Error);
}

TEST(EnvironmentGeometry, NeighboursAreSymmetricAndCrossEdges) {
    for (int grid = 0; grid < 2; ++grid) {
        const CubeMap cube(8);
        const ImageRGBA im(16, 8);
        const SphereTexels t = grid == 0 ? SphereTexels(cube) : SphereTexels(im, LatLongPixels::Centre);
        std::vector<std::size_t> nb, back;
        for (std::size_t i = 0; i < t.size(); ++i) {
            t.neighbours(i, nb);
            ASSERT_GE(nb.size(), 3u) << i;
            for (std::size_t k : nb) {
                ASSERT_NE(k, i);
                // Neighbours are close: within two texel diagonals.
                ASSERT_GT(glm::dot(t.direction(i), t.direction(k)), std::cos(grid == 0 ? 0.6 : 0.9))
                    << i << " " << k;
            }
        }
        // 4-neighbours are mutual (edge neighbours across cube edges and the lat-long seam too).
        std::size_t edges = 0, mutual = 0;
        for (std::size_t i = 0; i < t.size(); ++i) {
            t.neighbours(i, nb);
            for (std::size_t k : nb) {
                t.neighbours(k, back);
                ++edges;
                mutual += std::find(back.begin(), back.end(), i) != back.end();
            }
        }
        EXPECT_GT(double(mutual), 0.97 * double(edges)) << (grid == 0 ? "cube" : "latlong");
    }
}

TEST(EnvironmentStats, ConstantEnvironment) {
    const double L = 2.5;
    const glm::vec3 c = glm::vec3(float(L));
    for (int grid = 0; grid < 4; ++grid) {
        SCOPED_TRACE(grid);
        const CubeMap cube = cubeOf(grid == 0 ? 32 : 17, [&](const glm::dvec3&) { return c; });
        const ImageRGBA im =
            latLongOf(grid == 2 ? 128 : 51, grid == 2 ? 64 : 25, [&](const glm::dvec3&) { return c; });
        const EnvironmentStats s =
            grid < 2 ? computeEnvironmentStats(cube) : computeLatLongStats(im, LatLongPixels::Centre);
        EXPECT_NEAR(s.upwardIlluminance, kPi * L, 1e-6 * kPi * L); // E = pi L
        EXPECT_NEAR(s.meanLuminance, L, 1e-6 * L);
        EXPECT_NEAR(s.logMeanLuminance, L, 1e-6 * L);
        EXPECT_NEAR(s.minLuminance, L, 1e-6);
        EXPECT_NEAR(s.maxLuminance, L, 1e-6);
        EXPECT_NEAR(s.dynamicRangeStops, 0.0, 1e-9);
        EXPECT_NEAR(s.ev100, std::log2(L * 8.0), 1e-6); // log2(L * 100 / 12.5)
        EXPECT_NEAR(s.solidAngle, 4.0 * kPi, 1e-9);
    }
}

TEST(EnvironmentStats, AnalyticEnvironments) {
    // Upper hemisphere 1, lower 0 (even face size: the horizon is a texel boundary): E = pi, mean 1/2.
    const CubeMap half = cubeOf(32, [](const glm::dvec3& d) { return glm::vec3(d.y > 0 ? 1.0f : 0.0f); });
    EnvironmentStats s = computeEnvironmentStats(half);
    EXPECT_NEAR(s.upwardIlluminance, kPi, 1e-6);
    EXPECT_NEAR(s.meanLuminance, 0.5, 1e-6);
    EXPECT_NEAR(s.minLuminance, 0.0, 0.0);

    // L = cos(theta) above the horizon: E = integral of cos^2 = 2 pi / 3; texel-constant values make it
    // approximate (second order in the texel size).
    const CubeMap lobe =
        cubeOf(128, [](const glm::dvec3& d) { return glm::vec3(float(std::max(0.0, d.y))); });
    s = computeEnvironmentStats(lobe);
    EXPECT_NEAR(s.upwardIlluminance, 2.0 * kPi / 3.0, 1e-3 * 2.0 * kPi / 3.0);
    EXPECT_NEAR(s.meanLuminance, 0.25, 1e-3 * 0.25); // integral of cos over the hemisphere / 4 pi = 1/4

    // Two levels, 1 and 1024 (10 stops); colour does not matter beyond luminance.
    const CubeMap two = cubeOf(32, [](const glm::dvec3& d) {
        return d.x > 0.9 ? glm::vec3(1024.0f) : glm::vec3(0.0f, 1.0f / 0.7152f, 0.0f);
    });
    s = computeEnvironmentStats(two);
    EXPECT_NEAR(s.dynamicRangeStops, 10.0, 1e-4);
    EXPECT_NEAR(s.lowPercentileLuminance, 1.0, 1e-6);

    EXPECT_DOUBLE_EQ(ev100FromLuminance(1.0), 3.0); // Frostbite Table 7: EV100 3 <-> 1 cd/m2
    EXPECT_DOUBLE_EQ(ev100FromLuminance(4096.0), 15.0);
    EXPECT_TRUE(std::isnan(ev100FromLuminance(0.0)));
    EXPECT_TRUE(std::isnan(
        computeEnvironmentStats(cubeOf(4, [](const glm::dvec3&) { return glm::vec3(0.0f); })).ev100));

    // Zenith cap mean of a sky that is 3 at the zenith region only.
    const CubeMap zen =
        cubeOf(64, [](const glm::dvec3& d) { return glm::vec3(d.y > std::cos(0.2) ? 3.0f : 1.0f); });
    EXPECT_NEAR(zenithLuminance(SphereTexels(zen), kZenithCapDegrees), 3.0, 1e-6);
}

// On a cube, the zenith cap reads +Y's texels only when it is narrower than 45 degrees; the result is the
// one of every texel tested in order, to the last bit, on coarse grids (the nearest-texel fallback) too.
TEST(EnvironmentStats, ZenithLuminanceIsTheAllTexelLoops) {
    const auto sky = [](const glm::dvec3& d) {
        return glm::vec3(float(1.0 + 2.0 * d.y + 0.3 * d.x), float(0.5 + d.z * d.z), 0.25f);
    };
    for (int n : {1, 2, 3, 16, 33}) {
        const CubeMap cube = cubeOf(n, sky);
        const SphereTexels texels(cube);
        for (double cap : {1.0, 5.0, 30.0, 44.9, 60.0, 100.0}) {
            const std::vector<std::size_t> exclude = {2 * std::size_t(n) * n + std::size_t(n) / 2};
            double nearest = -1.0;
            for (std::size_t i = 0; i < texels.size(); ++i) {
                const glm::dvec3 v = texels.vectorSolidAngle(i);
                nearest = std::max(nearest, v.y / glm::length(v));
            }
            const double cosCap = std::min(std::cos(cap * kPi / 180.0), nearest - 1e-12);
            double energy = 0.0, omega = 0.0;
            for (std::size_t i = 0; i < texels.size(); ++i) {
                const glm::dvec3 v = texels.vectorSolidAngle(i);
                if (v.y / glm::length(v) < cosCap || i == exclude[0]) continue;
                energy += glm::dot(kRec709Luminance, glm::dvec3(texels.rgb(i))) * texels.solidAngle(i);
                omega += texels.solidAngle(i);
            }
            EXPECT_EQ(zenithLuminance(texels, cap, kRec709Luminance, exclude),
                      omega > 0.0 ? energy / omega : 0.0)
                << n << " texels, cap " << cap;
        }
    }
}

// The statistics (from per-face tables for a cube) equal the per-texel sums, and are the same to the last
// bit on one thread or many: a calibration factor made from them reaches every product, which must not
// depend on the machine (batch shards are byte-compared).
TEST(EnvironmentStats, MatchPerTexelSumsAndSameBitsOnAnyThreadCount) {
    const CubeMap cube = cubeOf(48, [](const glm::dvec3& d) {
        return glm::vec3(float(1.0 + 3.0 * std::max(0.0, d.y) + 0.5 * d.x), 0.7f, float(2.0 + d.z));
    });
    const glm::dvec3 weights(0.2126, 0.7152, 0.0722);
    const SphereTexels texels(cube);
    double energy = 0.0, upward = 0.0;
    for (std::size_t i = 0; i < texels.size(); ++i) {
        const double y = glm::dot(weights, glm::dvec3(texels.rgb(i)));
        energy += y * texels.solidAngle(i);
        upward += y * texels.upwardCosine(i);
    }
    const EnvironmentStats many = computeEnvironmentStats(cube, weights);
    EXPECT_NEAR(many.meanLuminance, energy / (4.0 * kPi), 1e-12 * many.meanLuminance);
    EXPECT_NEAR(many.upwardIlluminance, upward, 1e-12 * upward);
    EnvironmentStats one;
    {
        const tbb::global_control single(tbb::global_control::max_allowed_parallelism, 1);
        one = computeEnvironmentStats(cube, weights);
    }
    for (int repeat = 0; repeat < 4; ++repeat) {
        const EnvironmentStats again = computeEnvironmentStats(cube, weights);
        EXPECT_EQ(again.meanLuminance, one.meanLuminance);
        EXPECT_EQ(again.upwardIlluminance, one.upwardIlluminance);
        EXPECT_EQ(again.logMeanLuminance, one.logMeanLuminance);
        EXPECT_EQ(again.lowPercentileLuminance, one.lowPercentileLuminance);
    }
}

// The totals a calibration reads are the statistics' own to the last bit (the same sums without the
// samples): on a cube and a lat-long, with negative, zero and bright texels.
TEST(EnvironmentStats, TotalsAreTheStatisticsOwn) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> uni(-0.2f, 1.0f);
    CubeMap cube(40);
    for (ImageRGBA& face : cube.faces)
        for (glm::vec4& p : face.pixels)
            p = glm::vec4(uni(rng), uni(rng), uni(rng), 1.0f);
    cube.faces[2].at(7, 9) = glm::vec4(6.5e4f, 6.0e4f, 5.0e4f, 1.0f);
    ImageRGBA latlong(96, 48);
    for (glm::vec4& p : latlong.pixels)
        p = glm::vec4(uni(rng), uni(rng), 0.0f, 1.0f);
    const glm::dvec3 weights(0.2126, 0.7152, 0.0722);
    for (const SphereTexels& texels : {SphereTexels(cube), SphereTexels(latlong, LatLongPixels::Centre)}) {
        const EnvironmentStats stats = computeEnvironmentStats(texels, weights);
        const EnvironmentTotals totals = computeEnvironmentTotals(texels, weights);
        EXPECT_EQ(totals.solidAngle, stats.solidAngle);
        EXPECT_EQ(totals.minLuminance, stats.minLuminance);
        EXPECT_EQ(totals.maxLuminance, stats.maxLuminance);
        EXPECT_EQ(totals.meanLuminance, stats.meanLuminance);
        EXPECT_EQ(totals.upwardIlluminance, stats.upwardIlluminance);
    }
}

// The low percentile is the full sort's: the luminance at which the running solid angle of all positive
// texels in ascending order (ties by solid angle) first reaches 0.1 % of their total, whatever the
// selection does to get there. Luminances spread over many octaves with ties and zeros, on a cube and a
// lat-long (uneven solid angles).
TEST(EnvironmentStats, LowPercentileIsTheFullSorts) {
    const auto value = [](const glm::dvec3& d) {
        const double wave = std::sin(37.0 * d.x) * std::cos(23.0 * d.z) + 0.3 * d.y;
        const float y = wave < -0.9 ? 0.0f : float(std::exp2(std::round(12.0 * wave)));
        return glm::vec3(y);
    };
    const CubeMap cube = cubeOf(96, value);
    const ImageRGBA latlong = latLongOf(384, 192, value);
    for (const SphereTexels& texels : {SphereTexels(cube), SphereTexels(latlong, LatLongPixels::Centre)}) {
        std::vector<std::pair<float, float>> positive;
        double logOmega = 0.0;
        for (std::size_t i = 0; i < texels.size(); ++i) {
            const double y = glm::dot(kRec709Luminance, glm::dvec3(texels.rgb(i)));
            if (!(y > 0.0)) continue;
            positive.emplace_back(float(y), float(texels.solidAngle(i)));
            logOmega += texels.solidAngle(i);
        }
        std::sort(positive.begin(), positive.end());
        ASSERT_LT(positive.size(), texels.size()); // some texels are black
        const EnvironmentStats stats = computeEnvironmentStats(texels);
        double acc = 0.0;
        float expected = positive.back().first;
        for (const auto& [y, omega] : positive) {
            acc += omega;
            if (acc >= 0.001 * logOmega) {
                expected = y;
                break;
            }
        }
        EXPECT_EQ(stats.lowPercentileLuminance, expected);
    }
}

// ---------------------------------------------------------------------------------------------------
// Calibration factors

CalibrationSettings source(CalibrationSource s, double v = 0.0) {
    CalibrationSettings c;
    c.source = s;
    c.value = v;
    return c;
}

TEST(Calibration, FactorsOfEachSource) {
    const double L = 2.0;
    const CubeMap cube = cubeOf(16, [&](const glm::dvec3&) { return glm::vec3(float(L)); });
    EXPECT_EQ(computeCalibration(cube, source(CalibrationSource::None)).factor, 1.0);
    EXPECT_EQ(computeCalibration(cube, source(CalibrationSource::Scale, 3.75)).factor, 3.75);
    EXPECT_EQ(computeCalibration(cube, source(CalibrationSource::Ev100, 0.0)).factor, 1.2);
    EXPECT_EQ(computeCalibration(cube, source(CalibrationSource::Ev100, 10.0)).factor, 1.2 * 1024.0);
    EXPECT_EQ(computeCalibration(cube, source(CalibrationSource::Ev100, -2.5)).factor, 1.2 * std::exp2(-2.5));
    EXPECT_EQ(computeCalibration(cube, source(CalibrationSource::Radiometric)).factor, 683.0);

    const CalibrationRecord lux = computeCalibration(cube, source(CalibrationSource::Illuminance, 20000.0));
    EXPECT_NEAR(lux.factor, 20000.0 / (kPi * L), 1e-6 * lux.factor);
    EXPECT_NEAR(lux.measuredBefore, kPi * L, 1e-6);
    EXPECT_NEAR(lux.measuredAfter, 20000.0, 1e-6 * 20000.0);
    EXPECT_NEAR(lux.upwardIlluminanceAfter, 20000.0, 1e-6 * 20000.0);
    EXPECT_EQ(lux.units(), "cd/m2");

    const CalibrationRecord sky = computeCalibration(cube, source(CalibrationSource::SkyLuminance, 8000.0));
    EXPECT_NEAR(sky.factor, 4000.0, 1e-6 * 4000.0);
    EXPECT_TRUE(sky.sunMeasured);
    EXPECT_FALSE(sky.sunFound);

    // A sun of known E_perp on a flat sky: --sun-illuminance scales it to the target.
    CubeMap sunny = cubeOf(64, [](const glm::dvec3&) { return glm::vec3(0.2f); });
    SphereTexels t(sunny);
    const std::size_t k = (4 * 64 + 20) * 64 + 30;
    t.setRgb(k, t.rgb(k) + glm::vec3(float(1.5 / t.solidAngle(k))));
    const CalibrationRecord sun =
        computeCalibration(sunny, source(CalibrationSource::SunIlluminance, 100000.0));
    EXPECT_NEAR(sun.measuredBefore, 1.5, 1e-5 * 1.5);
    EXPECT_NEAR(sun.factor, 100000.0 / 1.5, 1e-5 * sun.factor);
    EXPECT_NEAR(sun.sunIlluminanceAfter, 100000.0, 1e-5 * 100000.0);
    applyCalibration(sunny, sun.factor);
    const SunDetection after = detectSun(sunny);
    ASSERT_TRUE(after.found);
    EXPECT_NEAR(after.light.illuminance, 100000.0, 1e-5 * 100000.0);
}

TEST(Calibration, UnusableValuesAreOneLineErrorsNamingTheOption) {
    const CubeMap flat = cubeOf(16, [](const glm::dvec3&) { return glm::vec3(1.0f); });
    const CubeMap black = cubeOf(16, [](const glm::dvec3&) { return glm::vec3(0.0f); });
    // The library names the setting ("calibration"), not a flag: callers put their own name in front
    // (CalibrateCli.ErrorsAreOneLineNonZeroAndWriteNothing checks the CLI's).
    auto message = [](const CubeMap& cube, CalibrationSettings s) -> std::string {
        try {
            computeCalibration(cube, s);
        } catch (const SettingError& e) {
            EXPECT_EQ(e.setting(), "calibration");
            EXPECT_EQ(std::string(e.what()).find("--"), std::string::npos) << e.what();
            return e.what();
        }
        return "";
    };
    EXPECT_EQ(message(flat, source(CalibrationSource::SunIlluminance, 1e5)).rfind("no sun detected: ", 0),
              0u);
    EXPECT_EQ(message(flat, source(CalibrationSource::Scale, -1.0)), "the value must be positive, got -1");
    EXPECT_EQ(message(flat, source(CalibrationSource::Scale, 0.0)), "the value must be positive, got 0");
    EXPECT_EQ(message(flat, source(CalibrationSource::Illuminance, NAN)),
              "the value must be a finite number");
    EXPECT_EQ(message(flat, source(CalibrationSource::Ev100, 1000.0)), "1000 is not an EV100 in -64..64");
    EXPECT_EQ(message(black, source(CalibrationSource::Illuminance, 1e4)),
              "the environment sends no light to an upward-facing surface");
    EXPECT_EQ(message(black, source(CalibrationSource::SkyLuminance, 1e4)),
              "the zenith of the environment is black");
    for (auto s : {source(CalibrationSource::Scale, -1.0), source(CalibrationSource::SunIlluminance, 1e5)})
        EXPECT_EQ(message(flat, s).find('\n'), std::string::npos);
}

TEST(Calibration, ApplyScalesColourNotAlphaAndMetadataRecordsIt) {
    CubeMap cube = cubeOf(4, [](const glm::dvec3&) { return glm::vec3(1.0f, 2.0f, 3.0f); });
    cube.faces[2].at(1, 1).w = 0.5f;
    applyCalibration(cube, 2.0);
    EXPECT_EQ(cube.faces[2].at(1, 1), glm::vec4(2.0f, 4.0f, 6.0f, 0.5f));
    const CalibrationRecord r = computeCalibration(cube, source(CalibrationSource::Illuminance, 5000.0));
    const auto kv = calibrationMetadata(r, "iblbake:");
    auto find = [&](const std::string& key) {
        for (const auto& [k, v] : kv)
            if (k == key) return v;
        return std::string("<absent>");
    };
    EXPECT_EQ(find("iblbake:calibration.source"), "illuminance");
    EXPECT_NEAR(std::stod(find("iblbake:calibration.factor")), r.factor, 1e-8 * r.factor);
    EXPECT_NEAR(std::stod(find("iblbake:calibration.measuredAfter")), 5000.0, 1e-5);
    EXPECT_EQ(find("iblbake:units"), "cd/m2");
    EXPECT_EQ(find("iblbake:calibration.quantity"), "upward illuminance");
}

// ---------------------------------------------------------------------------------------------------
// The commands, on the shared HDRIs

const fs::path kHdri = fs::path(IBLBAKE_SHARED_DIR) / "data" / "hdri";

#define REQUIRE_SHARED(name)                                                                                 \
    do {                                                                                                     \
        if (!fs::exists(kHdri / (name))) GTEST_SKIP() << (kHdri / (name)).string() << " is not present";     \
    } while (0)

nlohmann::json inspect(const fs::path& file) {
    const CliRun r = runCli("inspect --json " + file.string());
    EXPECT_EQ(r.exitCode, 0) << r.err;
    try {
        return nlohmann::json::parse(r.out);
    } catch (const std::exception& e) {
        ADD_FAILURE() << "inspect --json printed no JSON: " << e.what() << "\n" << r.out;
        return {};
    }
}

struct Pixels {
    int width = 0, height = 0, channels = 0;
    std::vector<float> data;
    std::map<std::string, std::string> attributes;
};

Pixels readPixels(const fs::path& file) {
    Pixels p;
    auto in = OIIO::ImageInput::open(file.string());
    EXPECT_TRUE(in) << OIIO::geterror();
    if (!in) return p;
    const OIIO::ImageSpec& spec = in->spec();
    p.width = spec.width;
    p.height = spec.height;
    p.channels = spec.nchannels;
    p.data.resize(std::size_t(p.width) * p.height * p.channels);
    EXPECT_TRUE(in->read_image(0, 0, 0, p.channels, OIIO::TypeDesc::FLOAT, p.data.data()));
    for (const OIIO::ParamValue& a : spec.extra_attribs)
        p.attributes[a.name().string()] = a.get_string();
    return p;
}

TEST(CalibrateCli, InspectReportsAnHdri) {
    REQUIRE_SHARED("rooitou_park_1k.hdr");
    const nlohmann::json j = inspect(kHdri / "rooitou_park_1k.hdr");
    EXPECT_EQ(j["width"], 1024);
    EXPECT_EQ(j["layout"], "latlong");
    EXPECT_EQ(j["faceSize"], 256);
    EXPECT_EQ(j["units"], "relative");
    EXPECT_TRUE(j["calibration"].is_null());
    EXPECT_GT(j["upwardIlluminance"].get<double>(), 0.0);
    EXPECT_GT(j["dynamicRange"]["stops"].get<double>(), 15.0);
    ASSERT_TRUE(j["sun"].is_object());
    EXPECT_NEAR(j["sun"]["elevationDegrees"].get<double>(), 10.4, 1.0); // SOURCES.md

    const CliRun text = runCli("inspect " + (kHdri / "potsdamer_platz_1k.hdr").string());
    EXPECT_EQ(text.exitCode, 0) << text.err;
    EXPECT_NE(text.out.find("no sun"), std::string::npos) << text.out;
    EXPECT_NE(text.out.find("EV100"), std::string::npos) << text.out;
}

TEST(CalibrateCli, IlluminanceRoundTrip) {
    for (const char* name : {"rooitou_park_1k.hdr", "KernerEnvCube.exr"}) {
        SCOPED_TRACE(name);
        if (!fs::exists(kHdri / name)) GTEST_SKIP() << name << " is not present";
        const fs::path dir = freshTempDir("calib_lux");
        const fs::path out = dir / "out.exr";
        const CliRun r =
            runCli("calibrate " + (kHdri / name).string() + " --illuminance 20000 -o " + out.string());
        ASSERT_EQ(r.exitCode, 0) << r.err;
        const nlohmann::json j = inspect(out);
        EXPECT_NEAR(j["upwardIlluminance"].get<double>(), 20000.0, 0.005 * 20000.0);
        EXPECT_EQ(j["units"], "cd/m2");
        EXPECT_EQ(j["calibration"]["iblbake:calibration.source"], "illuminance");
        EXPECT_EQ(ibl::test::entryCount(dir), 1u);
        fs::remove_all(dir);
    }
}

TEST(CalibrateCli, SunIlluminanceRoundTrip) {
    for (const char* name : {"rooitou_park_1k.hdr", "venice_sunset_1k.hdr"}) {
        SCOPED_TRACE(name);
        if (!fs::exists(kHdri / name)) GTEST_SKIP() << name << " is not present";
        const fs::path dir = freshTempDir("calib_sun");
        const fs::path out = dir / "out.exr";
        const CliRun r =
            runCli("calibrate " + (kHdri / name).string() + " --sun-illuminance 100000 -o " + out.string());
        ASSERT_EQ(r.exitCode, 0) << r.err;
        const nlohmann::json j = inspect(out);
        ASSERT_TRUE(j["sun"].is_object());
        EXPECT_NEAR(j["sun"]["illuminance"].get<double>(), 100000.0, 0.005 * 100000.0);
        fs::remove_all(dir);
    }
}

TEST(CalibrateCli, SkyLuminanceRoundTrip) {
    REQUIRE_SHARED("potsdamer_platz_1k.hdr");
    const fs::path dir = freshTempDir("calib_sky");
    const fs::path out = dir / "out.exr";
    const CliRun r = runCli("calibrate " + (kHdri / "potsdamer_platz_1k.hdr").string() +
                            " --sky-luminance 2000 -o " + out.string());
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const nlohmann::json j = inspect(out);
    EXPECT_NEAR(j["luminance"]["zenith"].get<double>(), 2000.0, 0.005 * 2000.0);
    EXPECT_EQ(j["calibration"]["iblbake:calibration.quantity"], "zenith luminance");
    fs::remove_all(dir);
}

TEST(CalibrateCli, ExactFactorsScaleEveryPixel) {
    REQUIRE_SHARED("venice_sunset_1k.hdr");
    const fs::path input = kHdri / "venice_sunset_1k.hdr";
    const Pixels in = readPixels(input);
    const fs::path dir = freshTempDir("calib_exact");
    struct Case {
        std::string option;
        double factor;
    };
    for (const Case& c : {Case{"--scale 3.5", 3.5}, Case{"--ev100 2.5", 1.2 * std::exp2(2.5)},
                          Case{"--ev100 -1", 0.6}, Case{"--radiometric", 683.0}}) {
        SCOPED_TRACE(c.option);
        const fs::path out = dir / "out.exr";
        const CliRun r = runCli("calibrate " + input.string() + " " + c.option + " -o " + out.string());
        ASSERT_EQ(r.exitCode, 0) << r.err;
        const Pixels p = readPixels(out);
        ASSERT_EQ(p.width, in.width);
        ASSERT_EQ(p.height, in.height);
        ASSERT_EQ(p.channels, 3);
        const float f = float(c.factor);
        std::size_t mismatches = 0;
        for (std::size_t i = 0; i < std::size_t(in.width) * in.height; ++i)
            for (int ch = 0; ch < 3; ++ch)
                mismatches += p.data[i * 3 + ch] != in.data[i * in.channels + ch] * f;
        EXPECT_EQ(mismatches, 0u);
        EXPECT_NEAR(std::stod(p.attributes.at("iblbake:calibration.factor")), c.factor, 1e-8 * c.factor);
        EXPECT_EQ(p.attributes.at("iblbake:units"), "cd/m2");
    }
    fs::remove_all(dir);
}

// Sum over a lat-long of value * exact pixel solid angle, in double (independent of the baker's grid class;
// the cells of the pixel-centre placement, latlong_pixels.h, as `calibrate` reads rooitou_park's pixels).
glm::dvec3 latLongEnergy(const Pixels& p) {
    auto edge = [](int k, int n) { return latLongPixelEdge(LatLongPixels::Centre, k, n); };
    glm::dvec3 e(0.0);
    for (int y = 0; y < p.height; ++y) {
        const double dz = std::cos(kPi * edge(y, p.height)) - std::cos(kPi * edge(y + 1, p.height));
        for (int x = 0; x < p.width; ++x) {
            const double omega = 2.0 * kPi * (edge(x + 1, p.width) - edge(x, p.width)) * dz;
            const float* c = &p.data[(std::size_t(y) * p.width + x) * p.channels];
            e += glm::dvec3(c[0], c[1], c[2]) * omega;
        }
    }
    return e;
}

TEST(CalibrateCli, ExtractSunWritesTheLightAndConservesEnergy) {
    REQUIRE_SHARED("rooitou_park_1k.hdr");
    const fs::path input = kHdri / "rooitou_park_1k.hdr";
    const fs::path dir = freshTempDir("calib_extract");
    const fs::path out = dir / "out.exr", kept = dir / "kept.exr", sunJson = dir / "sun.json";
    CliRun r = runCli("calibrate " + input.string() + " --sun-illuminance 100000 -o " + kept.string());
    ASSERT_EQ(r.exitCode, 0) << r.err;
    r = runCli("calibrate " + input.string() + " --sun-illuminance 100000 --extract-sun --sun-json " +
               sunJson.string() + " -o " + out.string());
    ASSERT_EQ(r.exitCode, 0) << r.err;
    std::ifstream jsonIn(sunJson);
    const std::string text((std::istreambuf_iterator<char>(jsonIn)), {});
    const DiskLight light = diskLightFromJson(text);
    // The energy the file lost is the light's (lat-long extraction, exact solid angles).
    const double removed =
        glm::dot(kRec709Luminance, latLongEnergy(readPixels(kept)) - latLongEnergy(readPixels(out)));
    EXPECT_NEAR(removed, light.illuminance, 0.005 * light.illuminance);
    // The calibration target is on the cube; the lat-long extraction agrees with it closely.
    EXPECT_NEAR(light.illuminance, 100000.0, 0.01 * 100000.0);
    EXPECT_NEAR(light.elevationDegrees(), 10.4, 1.0);
    const Pixels p = readPixels(out);
    EXPECT_NE(p.attributes.at("iblbake:sunLight").find("\"illuminanceLux\""), std::string::npos);
    EXPECT_EQ(p.attributes.at("iblbake:latlongPixels"), "centre");
    // Inspecting the residual finds no sun.
    const nlohmann::json j = inspect(out);
    EXPECT_TRUE(j["sun"].is_null());
    fs::remove_all(dir);
}

TEST(CalibrateCli, ErrorsAreOneLineNonZeroAndWriteNothing) {
    REQUIRE_SHARED("potsdamer_platz_1k.hdr");
    const fs::path dir = freshTempDir("calib_errors");
    const std::string out = (dir / "out.exr").string(), json = (dir / "sun.json").string();
    const std::string overcast = (kHdri / "potsdamer_platz_1k.hdr").string();
    struct Case {
        std::string args;
        std::string mention; // part of the one line
    };
    for (const Case& c :
         {Case{"calibrate " + overcast + " --scale 2 --ev100 3 -o " + out, "--scale"},
          Case{"calibrate " + overcast + " --illuminance 1000 --radiometric -o " + out, "--"},
          Case{"calibrate " + (dir / "missing.hdr").string() + " --scale 2 -o " + out, "missing.hdr"},
          // The flag that caused it, then the file, then the library's diagnosis.
          Case{"calibrate " + overcast + " --sun-illuminance 100000 -o " + out,
               "--sun-illuminance: " + overcast + ": no sun detected: "},
          Case{"calibrate " + overcast + " --scale 1 --extract-sun --sun-json " + json + " -o " + out,
               "--extract-sun: " + overcast + ": no sun detected: "},
          Case{"calibrate " + overcast + " --extract-sun -o " + out, "--sun-json"},
          Case{"calibrate " + overcast + " --scale -3 -o " + out,
               "--scale: " + overcast + ": the value must be positive, got -3"},
          Case{"calibrate " + overcast + " --layout spherical --scale 2 -o " + out, "--layout: 'spherical'"},
          Case{"calibrate " + overcast + " -o " + out, "calibration source"},
          Case{"inspect " + (dir / "missing.hdr").string(), "missing.hdr"}}) {
        SCOPED_TRACE(c.args);
        const CliRun r = runCli(c.args);
        EXPECT_NE(r.exitCode, 0);
        EXPECT_EQ(lineCount(r.err), 1) << r.err;
        EXPECT_EQ(r.err.rfind("iblbake: error:", 0), 0u) << r.err;
        EXPECT_NE(r.err.find(c.mention), std::string::npos) << r.err;
        EXPECT_EQ(ibl::test::entryCount(dir), 0u) << "partial output";
    }
    // The file is named in errors about its content.
    const CliRun r = runCli("calibrate " + overcast + " --sun-illuminance 100000 -o " + out);
    EXPECT_NE(r.err.find("potsdamer_platz_1k.hdr"), std::string::npos) << r.err;
    fs::remove_all(dir);
}

} // namespace
