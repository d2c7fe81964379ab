// DFG / diffuse LUT: against an independent fp64 integration of Frostbite Listing 18, across backends,
// and the analytic properties the split sum relies on.
#include <iblbake/baker/dfg_lut.h>
#include <iblbake/baker/dfg_reference.h>
#include <iblbake/core/error.h>
#include <iblbake/opencl/executor.h>

#include <brdf.h>
#include <dfg.h>

#include <gtest/gtest.h>

#include <cmath>
#include <sstream>

namespace {

using ibl::DfgSettings;
using ibl::Executor;
using ibl::ImageRGBA;

ImageRGBA bake(unsigned size, unsigned samples, const Executor& executor) {
    DfgSettings settings;
    settings.size = size;
    settings.sampleCount = samples;
    return ibl::bakeDfgLut(settings, executor);
}

Executor openclOrSkip() {
    std::ostringstream warnings;
    return Executor::create(ibl::Backend::Auto, "", warnings);
}

// The reference uses 2^18 samples: Listing 18's own NDF-sampled estimator is noisy at grazing views
// (at 65,536 samples it is still 1.1e-3 off its converged value at NoV = 1/64, r = 0.45), so fewer
// reference samples would measure the reference's error rather than ours.
TEST(DfgLut, MatchesIndependentListing18IntegrationWithin1e3) {
    const unsigned size = 32;
    // Frostbite Listing 18 in fp64, written out independently of kernels/ (iblbake/baker/dfg_reference.h).
    const std::vector<glm::dvec3> reference = ibl::referenceDfgGrid(size, 1u << 18);
    for (Executor executor : {Executor::cpu(), openclOrSkip()}) {
        ImageRGBA lut = bake(size, 4096, executor);
        double maxError = 0.0;
        for (unsigned k = 0; k < size * size; ++k) {
            glm::vec4 got = lut.pixels[k];
            ASSERT_TRUE(std::isfinite(got.x) && std::isfinite(got.y) && std::isfinite(got.z));
            glm::dvec3 error = glm::abs(glm::dvec3(got) - reference[k]);
            maxError = std::max({maxError, error.x, error.y, error.z});
        }
        std::printf("%s: max abs error vs Listing 18 (2^18 samples) %.2e\n", executor.description().c_str(),
                    maxError);
        EXPECT_LT(maxError, 1e-3) << executor.description();
    }
}

TEST(DfgLut, OpenCLAgreesWithCpu) {
    Executor cl = openclOrSkip();
    if (!cl.usesOpenCL()) GTEST_SKIP() << "no OpenCL device";
    ImageRGBA a = bake(64, 512, Executor::cpu()), b = bake(64, 512, cl);
    // Same functions and sample table on both; only FMA contraction and the order of float
    // operations differ, which moves a 512-sample mean by a few ulps of its terms.
    for (std::size_t i = 0; i < a.pixels.size(); ++i)
        for (int c = 0; c < 3; ++c)
            ASSERT_NEAR(a.pixels[i][c], b.pixels[i][c], 2e-5) << "texel " << i << " channel " << c;
}

TEST(DfgLut, EnergyBoundedAndMirrorLimit) {
    ImageRGBA lut = bake(64, 1024, Executor::cpu());
    for (const glm::vec4& p : lut.pixels) {
        ASSERT_TRUE(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z));
        ASSERT_GE(p.x, 0.0f);
        ASSERT_GE(p.y, 0.0f);
        ASSERT_LE(p.x + p.y, 1.0f + 1e-5f);
    }
    // Roughness -> 0 at NoV = 1 is a perfect mirror of f0 = f90 = 1: DFG1 + DFG2 -> 1.
    glm::vec4 mirror = lut.at(63, 0);
    EXPECT_NEAR(mirror.x + mirror.y, 1.0f, 1e-3f);
    // And the single-scattering albedo falls as roughness rises (energy lost to multiple scattering).
    EXPECT_LT(lut.at(32, 63).x + lut.at(32, 63).y, lut.at(32, 0).x + lut.at(32, 0).y - 0.1f);
}

TEST(DfgLut, ExactCornersAreFinite) {
    std::vector<glm::vec4> table(256);
    for (unsigned i = 0; i < 256; ++i)
        table[i] = ibl::dfgSampleEntry(i, 256);
    for (float NoV : {0.0f, 1e-7f, 0.5f, 1.0f})
        for (float r : {0.0f, 1e-7f, 0.5f, 1.0f}) {
            ibl::vec3 v = ibl::integrateDfgChunk(NoV, r, &table[0].x, 0, 256) / 256.0f;
            EXPECT_TRUE(std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z)) << NoV << " " << r;
            EXPECT_LE(v.x + v.y, 1.0f + 1e-5f);
        }
    // Roughness exactly 0: a mirror, so DFG1 + DFG2 = 1 at any view and DFG2 = Schlick's Fc(NoV).
    ibl::vec3 mirror = ibl::integrateDfgChunk(0.5f, 0.0f, &table[0].x, 0, 256) / 256.0f;
    EXPECT_NEAR(mirror.x + mirror.y, 1.0f, 1e-5f);
    EXPECT_NEAR(mirror.y, std::pow(0.5f, 5.0f), 1e-5f);
}

// Filament 4.7.2: scaling the single-scattering lobe by 1 + f0 (1/r - 1), r = DFG1 + DFG2, makes a
// white furnace (f0 = f90 = 1) reflect all energy at every roughness and view, and leaves smooth
// surfaces (where nothing is lost) unchanged.
TEST(DfgLut, EnergyCompensationRestoresWhiteFurnace) {
    ImageRGBA lut = bake(32, 1024, Executor::cpu());
    for (int y = 0; y < 32; ++y)
        for (int x = 0; x < 32; ++x) {
            glm::vec4 t = lut.at(x, y);
            glm::vec3 comp = ibl::energyCompensation(glm::vec3(1.0f), t.x, t.y);
            EXPECT_NEAR((t.x + t.y) * comp.x, 1.0f, 1e-4f);
            // Where nothing is lost (smooth, DFG1 + DFG2 = 1 up to quadrature error) the factor is 1.
            EXPECT_GE(comp.x, 1.0f - 1e-4f);
            // A dielectric loses less to multiple scattering than a white metal.
            EXPECT_LE(ibl::energyCompensation(glm::vec3(0.04f), t.x, t.y).x, comp.x + 1e-4f);
        }
    EXPECT_NEAR(ibl::energyCompensation(glm::vec3(1.0f), lut.at(31, 0).x, lut.at(31, 0).y).x, 1.0f, 1e-3f);
    EXPECT_GT(ibl::energyCompensation(glm::vec3(1.0f), lut.at(16, 31).x, lut.at(16, 31).y).x, 1.2f);
}

TEST(DfgLut, RejectsBadSettings) {
    EXPECT_THROW(bake(0, 16, Executor::cpu()), ibl::Error);
    EXPECT_THROW(bake(16, 0, Executor::cpu()), ibl::Error);
}

} // namespace
