// Area lights (kernels/area_lights.h) against their fp64 brute force (reference_area_lights.cpp): the sweep
// shape x roughness x distance x view of issue 15, with its table printed; the units of Frostbite Table 12
// and the inverse-square law far from the light; finite results where the geometry degenerates.
#include <iblbake/opencl/executor.h>
#include <iblbake/runtime/runtime_area_lights.h>

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>
#include <sstream>
#include <string>
#include <vector>

namespace {

using namespace ibl;

constexpr float kPi = 3.14159265358979f;
const char* kShapeNames[] = {"sphere", "disk", "rectangle"};

// Each shape one unit in size (sphere and disk of radius 0.5, a 1 x 1 rectangle) at the origin, emitting
// toward +z, 1000 lm.
AreaLight unitLight(uint32_t shape) {
    const glm::vec3 white(1.0f), up(0.0f, 0.0f, 1.0f);
    if (shape == IBL_AREA_SPHERE) return sphereAreaLight(glm::vec3(0.0f), 0.5f, white, 1000.0f);
    if (shape == IBL_AREA_DISK) return diskAreaLight(glm::vec3(0.0f), up, 0.5f, white, 1000.0f);
    return rectangleAreaLight(glm::vec3(0.0f), up, {1.0f, 0.0f, 0.0f}, 1.0f, 1.0f, white, 1000.0f);
}

// A white dielectric at `distance` from the light's centre, seen from `elevation` off the light's axis
// (in the xz-plane), its normal `viewAngle` off the direction to the light and its view the mirror image of
// that direction: the reflection points at the light's centre.
ShadingPoint sweepPoint(float distance, float elevation, float viewAngle, float perceptualRoughness) {
    glm::vec3 position = distance * glm::vec3(std::sin(elevation), 0.0f, std::cos(elevation));
    glm::vec3 toLight = -glm::normalize(position);
    glm::vec3 side = glm::normalize(glm::cross(toLight, glm::vec3(0.0f, 1.0f, 0.0f)));
    glm::vec3 normal = std::cos(viewAngle) * toLight + std::sin(viewAngle) * side;
    glm::vec3 view = 2.0f * glm::dot(normal, toLight) * normal - toLight;
    return makeShadingPoint(position, normal, view, glm::vec3(1.0f), 0.0f, perceptualRoughness);
}

const float kRoughness[] = {0.1f, 0.3f, 0.6f, 1.0f};
const float kDistance[] = {1.0f, 3.0f, 10.0f};
const float kElevation[] = {0.0f, 1.0f};             // radians: on the axis, and 57 degrees off it
const float kViewAngle[] = {0.0f, 0.5f, 1.0f, 1.4f}; // radians: 0, 29, 57, 80 degrees

// Mean relative errors |runtime - reference| / reference of one (shape, roughness, distance) cell.
struct CellError {
    double diffuseLambert = 0.0, diffuseDisney = 0.0;
    double specular = 0.0;        // view angles up to 57 degrees
    double specularGrazing = 0.0; // 80 degrees: the lobe stretched, the light partly below the horizon
    double reference = 0.0;       // the reference's own estimated error, relative, the largest of the cell
};

std::vector<ShadingPoint> cellPoints(float roughness, float distance) {
    std::vector<ShadingPoint> points;
    for (float elevation : kElevation)
        for (float view : kViewAngle)
            points.push_back(sweepPoint(distance, elevation, view, roughness));
    return points;
}

CellError sweepCell(uint32_t shape, float roughness, float distance) {
    const std::vector<ShadingPoint> points = cellPoints(roughness, distance);
    const AreaLight light = unitLight(shape);
    RuntimeOptions lambert, disney;
    lambert.energyCompensation = disney.energyCompensation = false;
    disney.diffuseModel = DiffuseModel::Disney;
    disney.specular = false;
    const std::vector<AreaLightResult> runtime = shadeAreaLightCpu(light, points, lambert);
    const std::vector<AreaLightResult> runtimeDisney = shadeAreaLightCpu(light, points, disney);
    const std::vector<AreaReference> reference = renderAreaLightReference(light, points, lambert);
    const std::vector<AreaReference> referenceDisney = renderAreaLightReference(light, points, disney);
    CellError e;
    int grazing = 0;
    for (std::size_t i = 0; i < points.size(); ++i) {
        const double rd = reference[i].value.diffuse.x, rs = reference[i].value.specular.x;
        const double rdd = referenceDisney[i].value.diffuse.x;
        EXPECT_GT(rd, 0.0);
        EXPECT_GT(rs, 0.0);
        e.diffuseLambert += std::abs(runtime[i].diffuse.x - rd) / rd;
        e.diffuseDisney += std::abs(runtimeDisney[i].diffuse.x - rdd) / rdd;
        const double specular = std::abs(runtime[i].specular.x - rs) / rs;
        const bool isGrazing = kViewAngle[i % std::size(kViewAngle)] > 1.2f;
        (isGrazing ? e.specularGrazing : e.specular) += specular;
        grazing += isGrazing ? 1 : 0;
        e.reference = std::max({e.reference, reference[i].diffuseError.x / rd,
                                reference[i].specularError.x / rs, referenceDisney[i].diffuseError.x / rdd});
    }
    const double n = double(points.size());
    e.diffuseLambert /= n, e.diffuseDisney /= n;
    e.specular /= n - grazing, e.specularGrazing /= grazing;
    return e;
}

// The sweep of issue 15 (3 shapes x 4 roughnesses x 3 distances x 2 elevations x 4 views), white dielectric.
// Bounds, this table's measurement with margin: diffuse 0.2% (the form factors are exact, the disk as a
// 16-gon of its area); Disney's diffuse, evaluated for one direction (Frostbite 4.7.4, eq. 45), 3%; specular
// up to 57 degrees 5% at 3 and 10 light sizes and 15% at 1, where a lobe as wide as the light is evaluated
// at one point for the whole light (-8 to -15% at r >= 0.6); at 80 degrees, where the highlight's lobe is
// stretched and the near light crosses the horizon (the representative point's known failure: Frostbite
// 4.7.5 on Karis's "doesn't behave well at grazing angles"), 15% beyond 1 light size and 60% at 1.
TEST(AreaLights, SweepAgainstTheBruteForce) {
    std::printf("| shape | r | d | diffuse Lambert | diffuse Disney | specular <= 57 deg | specular 80 deg | "
                "reference error |\n|---|---|---|---|---|---|---|---|\n");
    for (uint32_t shape : {IBL_AREA_SPHERE, IBL_AREA_DISK, IBL_AREA_RECTANGLE})
        for (float roughness : kRoughness)
            for (float distance : kDistance) {
                const CellError e = sweepCell(shape, roughness, distance);
                std::printf("| %s | %.1f | %.0f | %.2f%% | %.2f%% | %.2f%% | %.2f%% | %.3f%% |\n",
                            kShapeNames[shape], roughness, distance, 100.0 * e.diffuseLambert,
                            100.0 * e.diffuseDisney, 100.0 * e.specular, 100.0 * e.specularGrazing,
                            100.0 * e.reference);
                SCOPED_TRACE(std::string(kShapeNames[shape]) + " r " + std::to_string(roughness) + " d " +
                             std::to_string(distance));
                EXPECT_LT(e.reference, 0.002);
                EXPECT_LT(e.diffuseLambert, 0.002);
                EXPECT_LT(e.diffuseDisney, 0.03);
                EXPECT_LT(e.specular, distance > 1.0f ? 0.05 : 0.15);
                EXPECT_LT(e.specularGrazing, distance > 1.0f ? 0.15 : 0.60);
            }
}

// Frostbite Table 12 and eq. 38-39: far from a light of luminous power phi, the illuminance on a surface
// facing it is phi / (4 pi d^2) for a sphere, phi / (pi (d^2 + r^2)) for a disk and phi / (pi d^2) for a
// rectangle (a Lambertian emitter of intensity L A); and it falls with the inverse square of the distance.
TEST(AreaLights, UnitsAndInverseSquare) {
    RuntimeOptions lambert;
    lambert.specular = false;
    for (uint32_t shape : {IBL_AREA_SPHERE, IBL_AREA_DISK, IBL_AREA_RECTANGLE}) {
        SCOPED_TRACE(kShapeNames[shape]);
        const AreaLight light = unitLight(shape);
        std::vector<ShadingPoint> points;
        for (float d : {10.0f, 20.0f, 40.0f, 100.0f})
            points.push_back(sweepPoint(d, 0.3f, 0.0f, 0.5f));
        const std::vector<AreaLightResult> runtime = shadeAreaLightCpu(light, points, lambert);
        const std::vector<AreaReference> reference = renderAreaLightReference(light, points, lambert);
        for (std::size_t i = 0; i < points.size(); ++i) {
            const double d2 = glm::dot(points[i].position, points[i].position);
            // Radiance of a white Lambertian surface: E / pi.
            const double e = runtime[i].diffuse.x * kPi, eReference = reference[i].value.diffuse.x * kPi;
            const double expected = shape == IBL_AREA_SPHERE ? 1000.0 / (4.0 * kPi * d2)
                                    : shape == IBL_AREA_DISK ? 1000.0 / (kPi * (d2 + 0.25)) * std::cos(0.3)
                                                             : 1000.0 / (kPi * d2) * std::cos(0.3);
            EXPECT_NEAR(e / expected, 1.0, d2 > 150.0 ? 2e-3 : 5e-3) << "d^2 " << d2;
            EXPECT_NEAR(eReference / expected, 1.0, d2 > 150.0 ? 2e-3 : 5e-3) << "d^2 " << d2;
            if (i > 0) { // E d^2 stays the same
                const glm::vec3 previous = points[i - 1].position;
                EXPECT_NEAR(runtime[i - 1].diffuse.x * glm::dot(previous, previous) /
                                (runtime[i].diffuse.x * d2),
                            1.0, 1e-2);
            }
        }
    }
}

// Degenerate geometry: finite, non-negative results everywhere, zero where nothing is lit, and the
// reference agreeing on which is which.
TEST(AreaLights, HardCasesAreFinite) {
    const glm::vec3 up(0.0f, 0.0f, 1.0f), white(1.0f);
    std::vector<ShadingPoint> points;
    auto add = [&](glm::vec3 position, glm::vec3 normal, glm::vec3 view, float roughness) {
        points.push_back(makeShadingPoint(position, normal, view, white, 0.0f, roughness));
    };
    for (float roughness : {0.0f, 0.05f, 1.0f}) {
        add({0.3f, 0.0f, 0.0f}, up, up, roughness); // on the light (inside the rectangle/disk)
        add({2.0f, 0.0f, 0.0f}, up, up, roughness); // on the light's plane, beside it
        add({2.0f, 0.0f, 0.0f}, {-1.0f, 0.0f, 0.0f}, up, roughness); // ... facing it edge-on
        add({0.0f, 0.0f, -1.0f}, -up, -up, roughness);               // behind it
        add({0.0f, 0.0f, -1.0f}, up, up, roughness);                 // behind it, facing its back
        add({0.0f, 0.0f, 1.0f}, {1.0f, 0.0f, 0.0f}, up, roughness);  // grazing: the light on the horizon
        add({0.0f, 0.0f, 1.0f}, -up, {1.0f, 0.0f, 0.0f}, roughness); // grazing view
        add({0.0f, 0.0f, 1.0f}, -up, up, roughness);                 // view from behind the surface
        add({0.0f, 0.0f, 1e-4f}, -up, -up, roughness);               // almost on the light
        add({0.0f, 0.0f, 0.0f}, -up, -up, roughness);                // at the centre (inside the sphere)
        add({0.0f, 0.0f, 0.3f}, -up, -up, roughness);                // inside the sphere
        add({0.0f, 0.0f, 1.0f}, {0.0f, 0.0f, 0.0f}, {0.0f, 0.0f, 0.0f}, roughness); // zero vectors
    }
    for (uint32_t shape : {IBL_AREA_SPHERE, IBL_AREA_DISK, IBL_AREA_RECTANGLE}) {
        SCOPED_TRACE(kShapeNames[shape]);
        const AreaLight light = unitLight(shape);
        for (DiffuseModel model : {DiffuseModel::Lambert, DiffuseModel::Disney}) {
            RuntimeOptions options;
            options.diffuseModel = model;
            const std::vector<AreaLightResult> runtime = shadeAreaLightCpu(light, points, options);
            AreaReferenceSettings coarse; // finiteness only: a coarse grid, even for the mirrors
            coarse.gridSize = coarse.maxGridSize = 64;
            const std::vector<AreaReference> reference =
                renderAreaLightReference(light, points, options, coarse);
            for (std::size_t i = 0; i < points.size(); ++i) {
                SCOPED_TRACE("point " + std::to_string(i % 12) + " r " +
                             std::to_string(points[i].perceptualRoughness));
                for (int c = 0; c < 3; ++c) {
                    for (float v : {runtime[i].diffuse[c], runtime[i].specular[c]}) {
                        EXPECT_TRUE(std::isfinite(v));
                        EXPECT_GE(v, 0.0f);
                    }
                    EXPECT_TRUE(std::isfinite(reference[i].value.diffuse[c]));
                    EXPECT_TRUE(std::isfinite(reference[i].value.specular[c]));
                }
                // Behind a disk or rectangle, or on its plane: unlit, as in the reference.
                const bool unlit = shape != IBL_AREA_SPHERE && points[i].position.z <= 0.0f;
                if (unlit) {
                    EXPECT_EQ(runtime[i].diffuse.x + runtime[i].specular.x, 0.0f);
                    EXPECT_EQ(reference[i].value.total().x, 0.0);
                }
            }
        }
    }
}

// Random points around the lights (both sides, every orientation and view, above and below the horizon),
// metals and dielectrics of roughness in [minRoughness, 1].
std::vector<ShadingPoint> randomPoints(std::size_t count, float minRoughness) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f), u01(0.0f, 1.0f);
    std::vector<ShadingPoint> points(count);
    for (ShadingPoint& p : points) {
        glm::vec3 n = glm::normalize(glm::vec3(u(rng), u(rng), u(rng)) + glm::vec3(0.0f, 0.0f, 1e-3f));
        glm::vec3 v = glm::normalize(n + glm::vec3(u(rng), u(rng), u(rng)));
        p = makeShadingPoint(glm::vec3(3.0f * u(rng), 3.0f * u(rng), 3.0f * u(rng)), n, v,
                             glm::vec3(u01(rng), u01(rng), u01(rng)), u01(rng) < 0.5f ? 0.0f : 1.0f,
                             minRoughness + (1.0f - minRoughness) * u01(rng));
    }
    return points;
}

// Random geometry against the brute force: no point may be lit far brighter or darker than it is (a view
// under the horizon once made a 1e-3-nit highlight 48 nits). Bound: within a factor of 3, values under 1e-3
// of the luminance aside. Measured 2.4 (sphere, disk) and 1.8 (rectangle): where R misses the light, the
// overlap is empty and p_sc is the light's point nearest the footprint, where the lobe's tail is highest,
// standing for the whole light (a metal at r = 0.35, 1.4 light sizes away: 11.9 for 4.9 nits).
TEST(AreaLights, RandomPointsStayNearTheBruteForce) {
    const std::vector<ShadingPoint> points = randomPoints(96, 0.2f);
    for (uint32_t shape : {IBL_AREA_SPHERE, IBL_AREA_DISK, IBL_AREA_RECTANGLE}) {
        SCOPED_TRACE(kShapeNames[shape]);
        const AreaLight light = unitLight(shape);
        RuntimeOptions options;
        options.energyCompensation = false;
        AreaReferenceSettings settings;
        settings.gridSize = 128;
        const std::vector<AreaLightResult> runtime = shadeAreaLightCpu(light, points, options);
        const std::vector<AreaReference> reference =
            renderAreaLightReference(light, points, options, settings);
        const double floor = 1e-3 * light.luminance;
        double worstRatio = 1.0;
        for (std::size_t i = 0; i < points.size(); ++i)
            for (int c = 0; c < 3; ++c) {
                const double a = runtime[i].diffuse[c] + runtime[i].specular[c];
                const double b = reference[i].value.diffuse[c] + reference[i].value.specular[c];
                if (std::max(a, b) < floor) continue;
                worstRatio = std::max(worstRatio, std::max(a, floor) / std::max(b, floor));
                worstRatio = std::max(worstRatio, std::max(b, floor) / std::max(a, floor));
            }
        std::printf("%s: worst runtime/reference ratio over %zu random points %.3g\n", kShapeNames[shape],
                    points.size(), worstRatio);
        EXPECT_LT(worstRatio, 3.0);
    }
}

// kernels/area_lights.cl on OpenCL against the same header compiled as C++, over random points around each
// light (both sides, every orientation, metals and dielectrics, mirrors to rough). The compilers differ in
// FMA contraction and their sqrt/atan2/acos (measured: 3.9e-4 sphere, 3.8e-4 disk, 7.5e-4 rectangle).
TEST(AreaLights, OpenCLMatchesCpu) {
    std::ostringstream warnings;
    Executor executor = Executor::create(Backend::Auto, "", warnings);
    if (!executor.usesOpenCL()) GTEST_SKIP() << "no OpenCL device";
    const std::vector<ShadingPoint> points = randomPoints(4096, 0.0f);
    for (uint32_t shape : {IBL_AREA_SPHERE, IBL_AREA_DISK, IBL_AREA_RECTANGLE}) {
        SCOPED_TRACE(kShapeNames[shape]);
        RuntimeOptions options;
        options.diffuseModel = DiffuseModel::Disney;
        const std::vector<AreaLightResult> cpu = shadeAreaLightCpu(unitLight(shape), points, options);
        const std::vector<AreaLightResult> cl =
            shadeAreaLightOpenCL(executor.cl(), unitLight(shape), points, options);
        // Relative to max(|cpu|, 1e-3 of the light's luminance): where a sliver of the light stays above the
        // horizon its illuminance is ill-conditioned (a disk's 1e-5 differed by 10%).
        const double floor = 1e-3 * unitLight(shape).luminance;
        double worst = 0.0, lit = 0.0;
        for (std::size_t i = 0; i < points.size(); ++i)
            for (int c = 0; c < 3; ++c) {
                const float a = cpu[i].diffuse[c] + cpu[i].specular[c],
                            b = cl[i].diffuse[c] + cl[i].specular[c];
                const double rel = double(std::abs(a - b)) / std::max(floor, double(std::abs(a)));
                worst = std::max(worst, rel);
                lit += a > 0.0f ? 1.0 : 0.0;
            }
        std::printf("%s: OpenCL vs CPU over %zu points (%.0f%% lit): max relative difference %.3g\n",
                    kShapeNames[shape], points.size(), 100.0 * lit / (3.0 * points.size()), worst);
        EXPECT_GT(lit, 0.2 * 3.0 * points.size());
        EXPECT_LT(worst, 2e-3);
    }
}

} // namespace
