// The converged reference (runtime_reference.h renderConvergedReference): its estimated error bounds its
// actual error against closed forms (white furnace, one bright texel, a uniform sky with a sun texel) and
// against itself at a much higher effort, and it is under 0.5% per roughness column on the sample HDRI.
#include <iblbake/baker/material_preview.h>
#include <iblbake/baker/specular.h>
#include <iblbake/runtime/runtime_reference.h>

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>

using namespace ibl;

namespace {

constexpr double kPi = 3.14159265358979323846;

CubeMap uniformCube(int n, float value) {
    CubeMap cube(n);
    for (ImageRGBA& face : cube.faces)
        for (glm::vec4& p : face.pixels)
            p = glm::vec4(value, value, value, 1.0f);
    return cube;
}

// Points on a sphere facing +Z of perceptual roughness r: a grid x grid camera image (NoV >= 0.15).
// A sky brightening toward the zenith over a ground textured in stripes three texels wide.
CubeMap skyOverTexturedGround(int n) {
    CubeMap cube(n);
    for (int f = 0; f < 6; ++f)
        for (int y = 0; y < n; ++y)
            for (int x = 0; x < n; ++x) {
                const glm::vec3 d = glm::normalize(cubeFaceDirection(f, (x + 0.5f) / n, (y + 0.5f) / n));
                const float sky = d.y > 0 ? 1.0f + 2.0f * d.y : 0.3f + 0.1f * float(x % 3);
                cube.faces[f].at(x, y) = glm::vec4(sky, sky * 0.9f, sky * 0.8f, 1.0f);
            }
    return cube;
}

std::vector<ShadingPoint> spherePoints(float r, float metallic, int grid) {
    std::vector<ShadingPoint> points;
    for (int j = 0; j < grid; ++j)
        for (int i = 0; i < grid; ++i) {
            float u = (i + 0.5f) / grid * 2 - 1, v = (j + 0.5f) / grid * 2 - 1, z2 = 1 - u * u - v * v;
            if (z2 < 0.15f * 0.15f) continue;
            glm::vec3 n(u, v, std::sqrt(z2));
            points.push_back(
                makeShadingPoint(n, n, glm::vec3(0, 0, 1), glm::vec3(0.9f, 0.7f, 0.5f), metallic, r));
        }
    return points;
}

double lum(const glm::dvec3& c) {
    return 0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z;
}

// sum |a - b| / sum b over the points (luminance): a column's error.
// `cube` with texels [x0, x1) x [y0, y1) of face f set to `radiance`: a sun, a lamp or a window.
CubeMap withPatch(CubeMap cube, int f, int x0, int x1, int y0, int y1, glm::vec3 radiance) {
    for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; ++x)
            cube.faces[f].at(x, y) = glm::vec4(radiance, 1.0f);
    return cube;
}

double columnError(const std::vector<glm::dvec3>& a, const std::vector<glm::dvec3>& b) {
    double error = 0.0, sum = 0.0;
    for (std::size_t i = 0; i < a.size(); ++i)
        error += std::abs(lum(a[i]) - lum(b[i])), sum += lum(b[i]);
    return error / sum;
}

std::vector<glm::dvec3> totals(const ConvergedReference& r) {
    std::vector<glm::dvec3> out;
    for (const ReferenceResult& x : r.results)
        out.push_back(x.total());
    return out;
}

// sum lum(estimate) / sum lum(reference): the estimated change of a column's error.
double estimatedError(const ConvergedReference& r) {
    double error = 0.0, sum = 0.0;
    for (std::size_t i = 0; i < r.results.size(); ++i)
        error += lum(r.errorEstimate[i]), sum += lum(r.results[i].total());
    return error / sum;
}

// The reference of `points` at the default effort against the same integral at `high`'s: its actual error
// (columnError of the totals), its own estimate and the long run's own.
struct AgainstLongerRun {
    ConvergedReference reference;
    double actual, estimate, longRunEstimate;
};
AgainstLongerRun againstLongerRun(const CubeMap& cube, const std::vector<ShadingPoint>& points,
                                  const RuntimeOptions& options, const ConvergedReferenceSettings& high) {
    ConvergedReference ref = renderConvergedReference(cube, points, options);
    const ConvergedReference truth = renderConvergedReference(cube, points, options, high);
    const double actual = columnError(totals(ref), totals(truth)), estimate = estimatedError(ref);
    return {std::move(ref), actual, estimate, estimatedError(truth)};
}

} // namespace

// Lambert, base colour 1, in a uniform white environment: exactly 1 everywhere, through the dim path
// (no texel is bright) and through the bright path (every texel is).
TEST(ConvergedReference, WhiteFurnaceIsOneWithinItsEstimate) {
    const CubeMap white = uniformCube(32, 1.0f);
    RuntimeOptions options;
    options.specular = false;
    options.diffuseModel = DiffuseModel::Lambert;
    std::vector<ShadingPoint> points = spherePoints(0.5f, 0.0f, 9);
    for (ShadingPoint& p : points)
        p.baseColor = glm::vec3(1.0f);
    for (double brightFactor : {16.0, 0.5}) {
        ConvergedReferenceSettings settings;
        settings.brightFactor = brightFactor;
        settings.maxBrightTexels = 6 * 32 * 32;
        const ConvergedReference r = renderConvergedReference(white, points, options, settings);
        EXPECT_EQ(r.brightTexels, brightFactor < 1.0 ? 6u * 32 * 32 : 0u);
        const std::vector<glm::dvec3> exact(points.size(), glm::dvec3(1.0));
        const double actual = columnError(totals(r), exact), estimate = estimatedError(r);
        std::printf("furnace, bright factor %g: actual %.2e, estimated %.2e\n", brightFactor, actual,
                    estimate);
        EXPECT_LE(actual, estimate + 1e-6);
        EXPECT_LT(estimate, 5e-3);
    }
}

// One bright texel on black, seen by a rough metal (alpha 0.5, a lobe 40 texels wide): the integral is the
// texel's radiance x solid angle x the BRDF at its centre (the BRDF is flat across it), here in closed form.
TEST(ConvergedReference, SingleTexelMatchesTheClosedForm) {
    const int n = 128;
    CubeMap cube = uniformCube(n, 0.0f);
    const int x = 80, y = 70; // on +Z, off centre
    cube.faces[4].at(x, y) = glm::vec4(1000.0f, 1000.0f, 1000.0f, 1.0f);
    const glm::dvec3 l = glm::dvec3(cubeTexelDirection(4, x, y, n));
    const double omega = cubeTexelSolidAngle(x, y, n);
    RuntimeOptions options;
    options.diffuse = false;
    options.energyCompensation = false;
    const double r = std::sqrt(0.5), alpha = 0.5, a2 = alpha * alpha;
    std::vector<ShadingPoint> points;
    for (glm::vec3 normal : {glm::vec3(0, 0, 1), glm::normalize(glm::vec3(0.2f, -0.1f, 1.0f))})
        points.push_back(makeShadingPoint(glm::vec3(0), normal, normal, glm::vec3(1.0f), 1.0f, float(r)));
    const ConvergedReference ref = renderConvergedReference(cube, points, options);
    EXPECT_EQ(ref.brightTexels, 1u);
    for (std::size_t k = 0; k < points.size(); ++k) {
        const glm::dvec3 N(points[k].normal), V = N, h = glm::normalize(V + l);
        const double NoL = glm::dot(N, l), NoV = 1.0, NoH = glm::dot(N, h);
        const double d = NoH * NoH * (a2 - 1.0) + 1.0, D = a2 / (kPi * d * d);
        const double vis =
            0.5 / (NoL * std::sqrt(a2 + (1 - a2) * NoV * NoV) + NoV * std::sqrt(a2 + (1 - a2) * NoL * NoL));
        const double exact = 1000.0 * omega * D * vis * NoL; // F = f0 = 1
        const double got = ref.results[k].total().x, estimate = ref.errorEstimate[k].x;
        std::printf("single texel, point %zu: %.6g vs closed form %.6g, estimate %.2e\n", k, got, exact,
                    estimate);
        // The closed form's own error: the BRDF's curvature across one texel of a lobe 40 texels wide.
        EXPECT_LE(std::abs(got - exact), estimate + 1e-4 * exact);
        EXPECT_LT(std::abs(got - exact), 2e-3 * exact);
    }
}

// A uniform sky and a sun of 20000x its radiance on a few texels, on the columns of the preview: the
// estimate bounds the error against the same reference at 16x the samples and 4x the grid, and is small.
TEST(ConvergedReference, EstimateBoundsErrorWithASun) {
    const int n = 64;
    // +Y, off the zenith
    const CubeMap cube = withPatch(uniformCube(n, 1.0f), 2, 40, 42, 20, 22, {20000.0f, 19000.0f, 17000.0f});
    const RuntimeOptions options;
    ConvergedReferenceSettings high;
    high.samples = 8192;
    high.stepsPerScale = 32.0;
    for (float r : {0.0f, 0.1f, 0.3f, 0.6f, 1.0f}) {
        std::vector<ShadingPoint> points = spherePoints(r, 1.0f, 12);
        for (ShadingPoint& p : points) { // seen from above: the sun in the reflections
            p.normal = glm::vec3(p.normal.x, p.normal.z, -p.normal.y);
            p.view = glm::vec3(0, 1, 0);
        }
        const AgainstLongerRun check = againstLongerRun(cube, points, options, high);
        std::printf("sun, r = %.1f: actual %.2e, estimated %.2e\n", r, check.actual, check.estimate);
        EXPECT_LE(check.actual, check.estimate + 1e-5) << r;
        EXPECT_LT(check.estimate, 5e-3) << r;
    }
}

// A dim rest of wide range (a window 12x the sky beside it, under the bright threshold: the environment's
// luminance is sampled too, beside the visible normals and the cosine lobe): the estimate still bounds the
// error against the same reference at 8x the samples, and is small.
TEST(ConvergedReference, EstimateBoundsErrorWithEnvironmentSampling) {
    // +X, above the horizon
    const CubeMap cube = withPatch(skyOverTexturedGround(32), 0, 4, 10, 4, 12, {12.0f, 12.0f, 11.0f});
    const RuntimeOptions options;
    ConvergedReferenceSettings high;
    high.samples = 8192;
    for (float r : {0.0f, 0.5f, 1.0f})
        for (float metallic : {0.0f, 1.0f}) {
            std::vector<ShadingPoint> points = spherePoints(r, metallic, 8);
            for (ShadingPoint& p : points) { // seen from +X: the window in the reflections
                p.normal = glm::vec3(p.normal.z, p.normal.y, -p.normal.x);
                p.view = glm::vec3(1, 0, 0);
            }
            const AgainstLongerRun check = againstLongerRun(cube, points, options, high);
            EXPECT_EQ(check.reference.brightTexels, 0u);
            std::printf(
                "window, r = %.1f, metallic %.0f: actual %.2e, estimated %.2e (long run's own %.2e)\n", r,
                metallic, check.actual, check.estimate, check.longRunEstimate);
            // The half difference estimates the error's expected size, no strict bound: up to 1.18x under it
            // here (without environment sampling 0.9x, at 1.5x the error).
            EXPECT_LE(check.actual, 1.25 * check.estimate + check.longRunEstimate) << r;
            EXPECT_LT(check.estimate, 5e-3) << r;
        }
}

// The adaptive reference (issue 46) on a small sky with a sun of four texels and a textured ground, the
// balls grouped by roughness and metal, against the same integral at 16x the samples and 4x the grid steps
// of the fixed effort (the every-texel brute force, renderReference, was no judge here: 0.6-1.0% off itself
// between 32,768 and 65,536 samples per strategy on this sun), within that long run's own estimate: every
// group's actual error is under the 0.5% target, and the error it states is its size (at least half of it:
// the half difference of two sample sets estimates the error's expected size, it is no strict bound; here
// one group stated 0.050% for an actual 0.087%).
TEST(ConvergedReference, AdaptiveReferenceMeetsItsTargetAndStatesItsError) {
    // +Y, off the zenith
    const CubeMap cube =
        withPatch(skyOverTexturedGround(32), 2, 20, 22, 12, 14, {20000.0f, 19000.0f, 17000.0f});
    const RuntimeOptions options;
    std::vector<ShadingPoint> points;
    std::vector<int> group;
    const std::vector<float> roughness = {0.0f, 0.1f, 0.2f, 0.5f, 1.0f};
    for (std::size_t g = 0; g < 2 * roughness.size(); ++g)
        for (ShadingPoint p : spherePoints(roughness[g / 2], float(g % 2), 8)) {
            p.normal = glm::vec3(p.normal.x, p.normal.z, -p.normal.y); // seen from above: the sun reflected
            p.view = glm::vec3(0, 1, 0);
            points.push_back(p);
            group.push_back(int(g));
        }
    const AdaptiveReference adaptive = renderAdaptiveReference(cube, points, group, options, {}, {});
    ConvergedReferenceSettings high;
    high.samples = 16384;
    high.stepsPerScale = 32.0;
    const ConvergedReference truth = renderConvergedReference(cube, points, options, high);
    for (std::size_t g = 0; g < adaptive.groupErrorEstimate.size(); ++g) {
        std::vector<glm::dvec3> got, want;
        double truthEstimate = 0.0, sum = 0.0;
        for (std::size_t k = 0; k < points.size(); ++k)
            if (group[k] == int(g)) {
                got.push_back(adaptive.reference.results[k].total());
                want.push_back(truth.results[k].total());
                truthEstimate += lum(truth.errorEstimate[k]), sum += lum(truth.results[k].total());
            }
        const double actual = columnError(got, want), stated = adaptive.groupErrorEstimate[g];
        std::printf("group r = %.1f %s: %u samples, %g steps, stated %.3f%%, actual %.3f%% (long run's own "
                    "estimate %.3f%%)\n",
                    roughness[g / 2], g % 2 ? "metal" : "dielectric", adaptive.groupSamples[g],
                    adaptive.groupStepsPerScale[g], 100 * stated, 100 * actual, 100 * truthEstimate / sum);
        EXPECT_LE(stated, 5e-3) << g;
        EXPECT_LE(actual, 5e-3 + truthEstimate / sum) << g;
        EXPECT_GE(stated, 0.5 * (actual - truthEstimate / sum)) << g;
    }
}

// The fast LD reference at chosen texels against the every-texel brute force on a sky with a sun: the
// difference stays within its estimate, which is small.
TEST(ConvergedReference, FastLdAgreesWithTheBruteForceWithinItsEstimate) {
    CubeMap cube = skyOverTexturedGround(32);
    cube.faces[0].at(10, 12) = glm::vec4(30000.0f, 28000.0f, 25000.0f, 1.0f); // a one-texel sun on +X
    for (float r : {0.05f, 0.2f, 0.5f, 0.9f}) {
        const int size = 7; // texel centres off the source texels' corners
        const CubeMap brute = referenceSpecularLevel(cube, size, r);
        std::vector<CubeTexel> texels;
        for (int f = 0; f < 6; ++f)
            for (int y = 0; y < size; ++y)
                for (int x = 0; x < size; ++x)
                    texels.push_back({f, x, y});
        const LdTexelReference fast = referenceSpecularTexels(cube, size, r, texels);
        double error = 0.0, estimate = 0.0, sum = 0.0;
        for (std::size_t k = 0; k < texels.size(); ++k) {
            const glm::dvec3 want(brute.faces[texels[k].face].at(texels[k].x, texels[k].y));
            for (int c = 0; c < 3; ++c)
                error += std::abs(fast.value[k][c] - want[c]), estimate += fast.errorEstimate[k][c],
                    sum += want[c];
        }
        std::printf("LD r = %.2f: |fast - brute| %.2e, estimate %.2e\n", r, error / sum, estimate / sum);
        EXPECT_LE(error, estimate + 1e-4 * sum) << r;
        EXPECT_LT(estimate, 5e-3 * sum) << r;
    }
}

// On the sample HDRI (its 65,000-nit sun kept in, as the preview's reference sees it), the reference's own
// estimated error is under 0.5% in every roughness column of dielectric and metal spheres.
TEST(ConvergedReference, EstimateUnderHalfAPercentOnTheSampleHdri) {
    const CubeMap cube =
        previewReferenceCube(IBLBAKE_SOURCE_DIR "/data/rooitou_park_1k.hdr", 1.0, 256, LatLongPixels::Auto);
    for (int k = 0; k <= 10; ++k) {
        std::vector<ShadingPoint> points = spherePoints(k / 10.0f, 0.0f, 8);
        const std::vector<ShadingPoint> metal = spherePoints(k / 10.0f, 1.0f, 8);
        points.insert(points.end(), metal.begin(), metal.end());
        const ConvergedReference r = renderConvergedReference(cube, points, RuntimeOptions{});
        EXPECT_GT(r.brightTexels, 0u);
        std::printf("rooitou r = %.1f: estimated %.3f%%\n", k / 10.0, 100 * estimatedError(r));
        EXPECT_LT(estimatedError(r), 5e-3) << k;
    }
}

// Levels of few texels take more samples per texel (referenceSamplesPerHalf), so that the 1 x 1 level's
// reference, a mean of six texels, is converged below the errors it judges: on the sample HDRI at 256 px
// its own estimate is under 0.1% (0.027% measured; it read 0.29-0.76% on the shared HDRIs at 2 x 2048
// samples).
TEST(ConvergedReference, FewTexelLevelsTakeMoreSamples) {
    EXPECT_EQ(referenceSamplesPerHalf(1536), 2048u);
    EXPECT_EQ(referenceSamplesPerHalf(100000), 2048u);
    EXPECT_EQ(referenceSamplesPerHalf(96), 32768u);
    EXPECT_EQ(referenceSamplesPerHalf(6), 131072u);
    const CubeMap cube =
        previewReferenceCube(IBLBAKE_SOURCE_DIR "/data/rooitou_park_1k.hdr", 1.0, 256, LatLongPixels::Auto);
    std::vector<CubeTexel> texels;
    for (int f = 0; f < 6; ++f)
        texels.push_back({f, 0, 0});
    const LdTexelReference level = referenceSpecularTexels(cube, 1, 1.0f, texels);
    double estimate = 0.0, sum = 0.0;
    for (std::size_t k = 0; k < texels.size(); ++k)
        for (int c = 0; c < 3; ++c)
            estimate += level.errorEstimate[k][c], sum += level.value[k][c];
    std::printf("1 x 1 level, r = 1: estimated %.3f%%\n", 100 * estimate / sum);
    EXPECT_LT(estimate, 1e-3 * sum);
}
