// The shared BRDF and sampling math against closed forms and against Frostbite's own formulations.
#include <brdf.h>
#include <sampling.h>

#include <gtest/gtest.h>

#include <cmath>

namespace {

constexpr double kPi = 3.14159265358979323846;

// Integral over the hemisphere by a fine midpoint rule in (cos theta, phi).
template <class F>
double integrateHemisphere(F f, int n = 512) {
    double sum = 0.0;
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
            double c = (i + 0.5) / n, phi = 2.0 * kPi * (j + 0.5) / n, s = std::sqrt(1.0 - c * c);
            sum += f(ibl::vec3(float(s * std::cos(phi)), float(s * std::sin(phi)), float(c)));
        }
    return sum * 2.0 * kPi / (double(n) * n);
}

TEST(Brdf, GgxNdfIsNormalizedOverProjectedArea) {
    for (float alpha : {0.1f, 0.3f, 0.7f, 1.0f}) {
        double integral =
            integrateHemisphere([&](ibl::vec3 h) { return ibl::D_GGX(h.z, alpha) * h.z; }, 2048);
        EXPECT_NEAR(integral, 1.0, 2e-3) << "alpha " << alpha;
    }
}

TEST(Brdf, VisibilityMatchesFrostbiteListing2) {
    for (float alpha : {0.05f, 0.3f, 1.0f})
        for (float NoV : {0.01f, 0.4f, 1.0f})
            for (float NoL : {0.02f, 0.5f, 0.9f}) {
                // Frostbite Listing 2, V_SmithGGXCorrelated as printed.
                float a2 = alpha * alpha;
                float lv = NoL * std::sqrt((-NoV * a2 + NoV) * NoV + a2);
                float ll = NoV * std::sqrt((-NoL * a2 + NoL) * NoL + a2);
                float frostbite = 0.5f / (lv + ll);
                EXPECT_NEAR(ibl::V_SmithGGXCorrelated(NoV, NoL, alpha), frostbite, 1e-5f * frostbite);
                EXPECT_NEAR(ibl::G_SmithGGXCorrelated(NoV, NoL, alpha), frostbite * 4.0f * NoV * NoL, 1e-5f);
            }
    EXPECT_EQ(ibl::G_SmithGGXCorrelated(0.0f, 0.0f, 0.0f), 0.0f);
    EXPECT_TRUE(std::isfinite(ibl::V_SmithGGXCorrelated(0.0f, 0.0f, 0.5f)));
}

TEST(Brdf, DisneyDiffuseIsListing1) {
    // At roughness 0: fd90 = 2 LoH^2, energyFactor = 1; at NoL = NoV = 1 both scatter terms are 1.
    EXPECT_FLOAT_EQ(ibl::Fr_DisneyDiffuse(1.0f, 1.0f, 1.0f, 0.0f), 1.0f);
    EXPECT_FLOAT_EQ(ibl::Fr_DisneyDiffuse(1.0f, 1.0f, 1.0f, 1.0f), 1.0f / 1.51f);
    // Grazing with fd90 = 0.5 + 2 * 1 * 1: both Schlick terms equal fd90.
    EXPECT_NEAR(ibl::Fr_DisneyDiffuse(0.0f, 0.0f, 1.0f, 1.0f), 2.5f * 2.5f / 1.51f, 1e-5f);
}

TEST(Sampling, HammersleyIsStratified) {
    const unsigned n = 64;
    std::vector<int> bins(n, 0);
    for (unsigned i = 0; i < n; ++i) {
        ibl::float2 u = ibl::hammersley(i, n);
        ASSERT_GE(u.x, 0.0f);
        ASSERT_LT(u.y, 1.0f);
        ++bins[unsigned(u.y * n)];
    }
    for (int b : bins)
        EXPECT_EQ(b, 1);
}

TEST(Sampling, FrameIsOrthonormalEverywhereIncludingPoles) {
    for (ibl::vec3 n :
         {ibl::vec3(0, 0, 1), ibl::vec3(0, 0, -1), ibl::vec3(1, 0, 0), ibl::vec3(0, -1, 0),
          glm::normalize(ibl::vec3(1e-8f, 0, -1)), glm::normalize(ibl::vec3(0.3f, -0.5f, 0.8f))}) {
        ibl::Frame f = ibl::frameFromNormal(n);
        EXPECT_NEAR(glm::dot(f.t, f.b), 0.0f, 1e-6f);
        EXPECT_NEAR(glm::dot(f.t, f.n), 0.0f, 1e-6f);
        EXPECT_NEAR(glm::length(f.t), 1.0f, 1e-6f);
        EXPECT_NEAR(glm::length(f.b), 1.0f, 1e-6f);
        ibl::vec3 back = ibl::frameToWorld(f, ibl::frameToLocal(f, ibl::vec3(0.2f, 0.3f, 0.9f)));
        EXPECT_NEAR(glm::distance(back, ibl::vec3(0.2f, 0.3f, 0.9f)), 0.0f, 1e-5f);
    }
}

// The VNDF sampler's directional-albedo estimator E[G2/G1] equals the integral of the BRDF
// (D G2 / (4 NoV NoL)) NoL over the hemisphere computed by quadrature.
TEST(Sampling, VndfEstimatorMatchesQuadrature) {
    const unsigned n = 8192;
    for (float alpha : {0.2f, 0.6f, 1.0f})
        for (float NoV : {0.1f, 0.7f}) {
            ibl::vec3 v(std::sqrt(1 - NoV * NoV), 0, NoV);
            ibl::VndfView general = ibl::vndfPrepare(v, alpha), xz = ibl::vndfPrepareXZ(v, alpha);
            double mc = 0.0, mcXz = 0.0;
            for (unsigned i = 0; i < n; ++i) {
                ibl::float2 d = ibl::unitDiskPoint(ibl::hammersley(i, n));
                for (int k = 0; k < 2; ++k) {
                    ibl::vec3 h = ibl::vndfSample(k ? xz : general, d.x, d.y);
                    ibl::vec3 l = ibl::reflectAbout(v, h);
                    double w = l.z > 0
                                   ? ibl::G_SmithGGXCorrelated(NoV, l.z, alpha) / ibl::G1_SmithGGX(NoV, alpha)
                                   : 0;
                    (k ? mcXz : mc) += w / n;
                }
            }
            double quad = integrateHemisphere(
                [&](ibl::vec3 l) {
                    ibl::vec3 h = glm::normalize(l + v);
                    return ibl::D_GGX(h.z, alpha) * ibl::V_SmithGGXCorrelated(NoV, l.z, alpha) * l.z;
                },
                2048);
            EXPECT_NEAR(mc, quad, 3e-3) << alpha << " " << NoV;
            EXPECT_NEAR(mcXz, quad, 3e-3) << alpha << " " << NoV;
        }
}

} // namespace
