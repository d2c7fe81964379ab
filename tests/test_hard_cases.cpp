// Inputs where bakers usually break, across every stage: all-zero and single-texel environments,
// denormals, values past half-float range, extreme calibration factors. Nothing may produce NaN/Inf or
// throw where a result exists; energy is kept where it must be.
#include "test_support.h"

#include <iblbake/calibration.h>
#include <iblbake/irradiance.h>
#include <iblbake/ktx2.h>
#include <iblbake/sh.h>
#include <iblbake/specular.h>
#include <iblbake/sun.h>

#include <gtest/gtest.h>

#include <limits>

namespace fs = std::filesystem;

namespace {

using namespace ibl;
using namespace ibl::test;

void expectFiniteNonNegative(const CubeMap& cube, const char* what) {
    for (const ImageRGBA& face : cube.faces)
        for (const glm::vec4& p : face.pixels)
            for (int c = 0; c < 3; ++c) {
                ASSERT_TRUE(std::isfinite(p[c])) << what;
                ASSERT_GE(p[c], 0.0f) << what;
            }
}

void expectFinite(const ShRgb& sh, const char* what) {
    for (const glm::dvec3& c : sh)
        ASSERT_TRUE(std::isfinite(c.x) && std::isfinite(c.y) && std::isfinite(c.z)) << what;
}

// Every stage on one environment: the specular chain, the irradiance cube (sampled and from SH), the SH
// with the automatic window, and sun detection.
void bakeEverything(const CubeMap& env, const char* what) {
    for (Executor executor : {Executor::cpu(), openclOrCpu()}) {
        for (const CubeMap& level : bakeSpecular(env, SpecularSettings{}, executor).levels)
            expectFiniteNonNegative(level, what);
        IrradianceSettings irradiance;
        irradiance.faceSize = 8;
        expectFiniteNonNegative(bakeIrradianceCube(env, irradiance, executor), what);
    }
    DiffuseSH sh = bakeDiffuseSH(env, ShWindowSettings{});
    expectFinite(sh.radiance, what);
    expectFinite(sh.irradiance, what);
    expectFiniteNonNegative(irradianceCubeFromSH(sh.irradiance, 8), what);
    SunDetection sun = detectSun(env);
    EXPECT_TRUE(std::isfinite(sun.peakLuminance)) << what;
}

TEST(HardCases, AllZeroEnvironmentBakesToZero) {
    CubeMap black = makeCube(16, [](glm::dvec3) { return glm::dvec3(0.0); });
    bakeEverything(black, "all zero");
    for (const CubeMap& level : bakeSpecular(black, SpecularSettings{}, Executor::cpu()).levels)
        for (const ImageRGBA& face : level.faces)
            for (const glm::vec4& p : face.pixels)
                ASSERT_EQ(glm::vec3(p), glm::vec3(0.0f));
    EXPECT_FALSE(detectSun(black).found);
}

TEST(HardCases, BlackExceptOneTexelStaysFiniteAndShKeepsItsEnergy) {
    CubeMap env = makeCube(16, [](glm::dvec3) { return glm::dvec3(0.0); });
    env.faces[2].at(5, 9) = glm::vec4(1e6f, 1e6f, 1e6f, 1.0f);
    bakeEverything(env, "one texel");
    // The irradiance from SH integrates the texel's energy exactly: E at its own direction is
    // L * solid angle (band-limited, so allow the L2 truncation: > half and < twice).
    DiffuseSH sh = bakeDiffuseSH(env, ShWindowSettings{false, ShWindow::None, {}});
    glm::dvec3 d = texelCentre(2, 5, 9, 16);
    double expected = 1e6 * cubeTexelSolidAngle(5, 9, 16);
    double got = evalPrescaledSH(sh.irradiance, d).y;
    EXPECT_GT(got, 0.5 * expected);
    EXPECT_LT(got, 2.0 * expected);
}

TEST(HardCases, DenormalAndHugeValuesStayFinite) {
    const float denormal = std::numeric_limits<float>::denorm_min() * 7.0f;
    CubeMap env = makeCube(8, [&](glm::dvec3 d) { return glm::dvec3(d.y > 0.0 ? denormal : 1e30); });
    bakeEverything(env, "denormals and 1e30");
}

TEST(HardCases, TinyAndHugeCalibrationFactors) {
    auto sky = [](glm::dvec3 d) { return glm::dvec3(0.5 + 0.5 * d.y); };
    CalibrationSettings toTenThousandLux;
    toTenThousandLux.source = CalibrationSource::Illuminance;
    toTenThousandLux.value = 10000.0;
    const double unscaledFactor = computeCalibration(makeCube(8, sky), toTenThousandLux).factor;
    for (double factor : {1e-30, 1e-12, 1e12, 1e30}) {
        CubeMap env = makeCube(8, sky);
        applyCalibration(env, factor);
        bakeEverything(env, "calibrated");
        // Calibrating the pre-scaled map to the same illuminance undoes the pre-scale exactly.
        CalibrationRecord record = computeCalibration(env, toTenThousandLux);
        ASSERT_TRUE(std::isfinite(record.factor) && record.factor > 0.0) << factor;
        EXPECT_NEAR(record.factor * factor / unscaledFactor, 1.0, 1e-5) << factor;
    }
}

TEST(HardCases, ValuesPastHalfRangeAreClampedAndCountedInKtx2) {
    CubeMap env = makeCube(4, [](glm::dvec3) { return glm::dvec3(1e6); });
    CubeMapChain chain = bakeSpecular(env, SpecularSettings{}, Executor::cpu());
    fs::path dir = fs::temp_directory_path() / ("iblbake_hard_" + std::to_string(::getpid()));
    fs::create_directories(dir);
    Ktx2WriteStats stats = writeKtx2Cube(dir / "big.ktx2", chain, Ktx2Format::RGBA16F, {});
    EXPECT_EQ(stats.clampedTexels, 6u * (16 + 4 + 1));
    for (const auto& level : readKtx2(dir / "big.ktx2").levels)
        for (const ImageRGBA& face : level)
            for (const glm::vec4& p : face.pixels)
                ASSERT_EQ(p.x, 65504.0f);
    fs::remove_all(dir);
}

} // namespace
