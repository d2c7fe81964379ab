// Specular LD chain: analytic cases, the brute-force reference, and backend agreement.
#include <iblbake/baker/specular.h>
#include <iblbake/core/error.h>

#include <cube.h>

#include "bright_split.h"
#include "lobe_integral.h"

#include "test_support.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <sstream>

namespace {

using namespace ibl;
using namespace ibl::test;

// The residual made in the source itself (withResidualInPlace, what bakeSpecular uses) is applyBrightSplit's
// residual bit for bit, with the same bright texels, and the source holds its own texels again afterwards,
// also when the work on the residual throws.
TEST(Specular, ResidualInPlaceIsTheSplitAndLeavesTheSourceAsItWas) {
    CubeMap source(8);
    for (int f = 0; f < 6; ++f)
        for (std::size_t i = 0; i < source.faces[f].pixels.size(); ++i)
            source.faces[f].pixels[i] =
                glm::vec4(0.1f + 0.01f * float(i % 7), 0.2f, 0.3f + 0.001f * float(f), 1.0f);
    source.faces[2].at(3, 4) = glm::vec4(5e4f, 4e4f, 3e4f, 1.0f); // a sun across two texels
    source.faces[2].at(4, 4) = glm::vec4(2e4f, 2e4f, 1e4f, 1.0f);
    const CubeMap original = source;
    const BrightChoice choice = chooseBrightTexels(source, 32.0f, 4096);
    ASSERT_EQ(choice.texels.size(), 2u);
    const BrightSplit split = applyBrightSplit(original, choice);
    auto sameBits = [](const CubeMap& a, const CubeMap& b) {
        for (int f = 0; f < 6; ++f)
            if (std::memcmp(a.faces[f].pixels.data(), b.faces[f].pixels.data(),
                            a.faces[f].pixels.size() * sizeof(glm::vec4)) != 0)
                return false;
        return true;
    };
    bool sawResidual = false;
    const BrightTexels bright = withResidualInPlace(
        source, choice, [&](const CubeMap& residual) { sawResidual = sameBits(residual, split.residual); });
    EXPECT_TRUE(sawResidual);
    EXPECT_EQ(bright.entries, split.bright.entries);
    EXPECT_EQ(bright.clusters, split.bright.clusters);
    EXPECT_TRUE(sameBits(source, original));
    EXPECT_THROW(withResidualInPlace(source, choice, [](const CubeMap&) { throw Error("stop"); }), Error);
    EXPECT_TRUE(sameBits(source, original));
}

// A sky-like environment: bright upper hemisphere with a gradient, a warm lobe, a dark ground.
glm::vec3 skyLike(glm::vec3 d) {
    glm::vec3 sky = glm::vec3(0.4f, 0.6f, 1.0f) * (0.5f + 0.5f * std::max(d.y, 0.0f));
    glm::vec3 ground = glm::vec3(0.1f, 0.08f, 0.05f);
    float lobe = std::pow(std::max(glm::dot(d, glm::normalize(glm::vec3(0.5f, 0.4f, 0.6f))), 0.0f), 32.0f);
    return (d.y > 0 ? sky : ground) + glm::vec3(20.0f, 15.0f, 10.0f) * lobe;
}

// lobeIntegral's closed form against the integral of D(h) NoL over the light's polar angle theta (l at theta
// from N = V, h at theta / 2: 2 pi sin(theta) d(theta)), a parametrization it does not use, by Simpson's rule
// on 2^21 steps (converged: halving them changes no result by 1e-12). Across alpha = 1, where the closed form
// takes its first-order branch, and at the mirror's W = 4.
TEST(Specular, LobeIntegralIsTheIntegralOfDTimesNoL) {
    const auto byTheta = [](double alpha) {
        const int steps = 1 << 21;
        const double h = 0.5 * M_PI / steps, a2 = alpha * alpha;
        double sum = 0.0;
        for (int i = 0; i <= steps; ++i) {
            const double theta = i * h, cosHalf = std::cos(0.5 * theta);
            const double f = cosHalf * cosHalf * (a2 - 1.0) + 1.0;
            const double value = a2 / (M_PI * f * f) * std::cos(theta) * 2.0 * M_PI * std::sin(theta);
            sum += value * (i == 0 || i == steps ? 1.0 : i % 2 ? 4.0 : 2.0);
        }
        return sum * h / 3.0;
    };
    for (double alpha : {0.01, 0.03, 0.0625, 0.2, 0.5, 0.9, 1.0 - 1e-7, 1.0, 1.0 + 1e-7, 1.0 - 1e-5})
        EXPECT_NEAR(lobeIntegral(alpha), byTheta(alpha), 1e-9 * byTheta(alpha)) << "alpha " << alpha;
    EXPECT_EQ(lobeIntegral(0.0), 4.0);
    EXPECT_NEAR(lobeIntegral(1e-4), 4.0, 1e-5);
}

TEST(Specular, WhiteFurnaceEveryLevelEveryTexel) {
    CubeMap constant = makeCube(32, [](glm::vec3) { return glm::vec3(0.75f); });
    for (Executor executor : {Executor::cpu(), openclOrCpu()}) {
        CubeMapChain chain = bakeSpecular(constant, SpecularSettings{}, executor);
        ASSERT_EQ(chain.levels.size(), 6u);
        for (const CubeMap& level : chain.levels)
            for (const ImageRGBA& face : level.faces)
                for (const glm::vec4& p : face.pixels)
                    for (int c = 0; c < 3; ++c)
                        ASSERT_NEAR(p[c], 0.75f, 0.75f * 1e-4f) << executor.description();
    }
}

TEST(Specular, MirrorLevelIsTheSourceAndMappingIsEq63) {
    CubeMap source = makeCube(16, skyLike);
    CubeMapChain chain = bakeSpecular(source, SpecularSettings{}, Executor::cpu());
    ASSERT_EQ(chain.levels.size(), 5u);
    for (int f = 0; f < 6; ++f)
        EXPECT_EQ(chain.levels[0].faces[f].pixels, source.faces[f].pixels);
    for (int m = 0; m < 5; ++m)
        EXPECT_EQ(chain.levels[m].faceSize, 16 >> m);
    EXPECT_FLOAT_EQ(perceptualRoughnessForLevel(2, 5, MipMapping::Frostbite), 0.25f);
    EXPECT_FLOAT_EQ(perceptualRoughnessForLevel(4, 5, MipMapping::Frostbite), 1.0f);
    EXPECT_FLOAT_EQ(perceptualRoughnessForLevel(2, 5, MipMapping::Linear), 0.5f);
}

TEST(Specular, OpenCLAgreesWithCpu) {
    Executor cl = openclOrCpu();
    if (!cl.usesOpenCL()) GTEST_SKIP() << "no OpenCL device";
    CubeMap source = makeCube(32, skyLike);
    CubeMapChain a = bakeSpecular(source, SpecularSettings{}, Executor::cpu());
    CubeMapChain b = bakeSpecular(source, SpecularSettings{}, cl);
    // Same functions and tables; FMA contraction and summation order differ between the compilers.
    for (std::size_t m = 0; m < a.levels.size(); ++m)
        EXPECT_LT(relativeMeanAbsError(b.levels[m], a.levels[m]), 1e-5) << m;
}

TEST(Specular, ProductionPresetWithin2PercentOfBruteForce) {
    CubeMap source = makeCube(32, skyLike);
    CubeMapChain chain = bakeSpecular(source, SpecularSettings{}, openclOrCpu());
    for (int m = 1; m < int(chain.levels.size()); ++m) {
        float r = perceptualRoughnessForLevel(m, int(chain.levels.size()), MipMapping::Frostbite);
        CubeMap ref = referenceSpecularLevel(source, chain.levels[m].faceSize, r);
        double error = relativeMeanAbsError(chain.levels[m], ref);
        std::printf("level %d r=%.3f relative MAE %.4f\n", m, r, error);
        EXPECT_LT(error, 0.02) << "level " << m;
    }
}

TEST(Specular, BrightSunStaysFiniteAndBounded) {
    const float sun = 1e6f;
    CubeMap source = makeCube(32, [](glm::vec3) { return glm::vec3(1.0f); });
    source.faces[4].at(20, 9) = glm::vec4(sun, sun, sun, 1.0f);
    CubeMapChain chain = bakeSpecular(source, SpecularSettings{}, openclOrCpu());
    for (const CubeMap& level : chain.levels)
        for (const ImageRGBA& face : level.faces)
            for (const glm::vec4& p : face.pixels)
                for (int c = 0; c < 3; ++c) {
                    ASSERT_TRUE(std::isfinite(p[c]));
                    ASSERT_GE(p[c], 0.0f);
                    ASSERT_LE(p[c], sun);
                }
}

TEST(Specular, TinyFacesAndBadSizes) {
    CubeMap one = makeCube(1, [](glm::vec3 d) { return glm::abs(d); });
    EXPECT_EQ(bakeSpecular(one, SpecularSettings{}, Executor::cpu()).levels.size(), 1u);
    CubeMap two = makeCube(2, [](glm::vec3) { return glm::vec3(2.0f); });
    CubeMapChain chain = bakeSpecular(two, SpecularSettings{}, openclOrCpu());
    ASSERT_EQ(chain.levels.size(), 2u);
    for (const ImageRGBA& face : chain.levels[1].faces)
        EXPECT_NEAR(face.pixels[0].x, 2.0f, 2e-4f);
    EXPECT_THROW(bakeSpecular(makeCube(12, skyLike), SpecularSettings{}, Executor::cpu()), Error);
}

} // namespace
