// Runtime vs the brute-force reference (Frostbite Appendix A): sphere grids over perceptual roughness x
// dielectric/metal under a synthetic sky and under every HDRI of ../shared/data/hdri (skipped when absent);
// distance-based roughness on a glossy floor near a textured wall; the sun as a disk light.
#include "runtime_test_support.h"

#include <iblbake/baker/ingest.h>
#include <iblbake/baker/sun.h>
#include <iblbake/runtime/runtime_reference.h>

#include <filesystem>
#include <numeric>

namespace fs = std::filesystem;

namespace {

using namespace ibl;
using namespace rt_test;

constexpr int kColumns = 11; // perceptual roughness 0, 0.1, ..., 1
const glm::vec3 kDielectricBase(0.8f, 0.55f, 0.35f);
const glm::vec3 kMetalBase(0.95f, 0.64f, 0.54f);

// Points of a unit sphere seen by orthographic cameras from four directions (a 9 x 9 pixel grid each,
// pixels whose normal has NoV >= 0.15), one material.
std::vector<ShadingPoint> sphereGrid(float perceptualRoughness, float metallic, glm::vec3 baseColor) {
    const glm::vec3 cameras[] = {glm::vec3(0, 0, 1), glm::vec3(0, 0, -1), glm::vec3(1, 0, 0),
                                 glm::normalize(glm::vec3(0.3f, 0.9f, 0.3f))};
    std::vector<ShadingPoint> points;
    for (glm::vec3 c : cameras) {
        glm::vec3 right =
            glm::normalize(glm::cross(std::abs(c.y) < 0.9f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0), c));
        glm::vec3 up = glm::cross(c, right);
        for (int j = 0; j < 9; ++j)
            for (int i = 0; i < 9; ++i) {
                float u = (i + 0.5f) / 9 * 2 - 1, v = (j + 0.5f) / 9 * 2 - 1;
                float z2 = 1 - u * u - v * v;
                if (z2 < 0.15f * 0.15f) continue;
                glm::vec3 n = u * right + v * up + std::sqrt(z2) * c;
                points.push_back(makeShadingPoint(n, n, c, baseColor, metallic, perceptualRoughness));
            }
    }
    return points;
}

// LD of the environment in direction d for a perceptual roughness, integrated exactly (N = V = R, GGX
// importance sampling, 4096 samples of the continuous environment): what a perfect LD chain would return.
glm::dvec3 exactLd(const ReferenceLighting& environment, glm::vec3 d, float perceptualRoughness) {
    const uint32_t n = 4096;
    Frame frame = frameFromNormal(vec3(d));
    float alpha = std::max(perceptualRoughness * perceptualRoughness, 1e-4f);
    glm::dvec3 sum(0.0);
    double weight = 0.0;
    for (uint32_t i = 0; i < n; ++i) {
        float2 u = hammersley(i, n);
        float phi = 2.0f * IBL_PI * u.y;
        vec3 l = reflectAbout(v3(0, 0, 1), sampleGGXHalfVector(u.x, std::cos(phi), std::sin(phi), alpha));
        if (l.z <= 0.0f) continue;
        sum += environment.radiance(glm::vec3(0.0f), glm::normalize(glm::dvec3(frameToWorld(frame, l)))) *
               double(l.z);
        weight += l.z;
    }
    return sum / weight;
}

// The runtime with its LD lookup replaced by exactLd at the same (dominant) direction: everything else
// (DFG LUT, energy compensation, SH diffuse, sun) as the runtime. Its error against the reference is the
// method's floor (split sum, dominant direction, SH, representative point); the runtime's excess over it is
// the LD chain's (levels, resolution, trilinear lookup). Distant probe only.
std::vector<glm::vec4> splitSumWithExactLd(const ProbeSet& set, const ReferenceLighting& environment,
                                           std::span<const ShadingPoint> points,
                                           const RuntimeOptions& options) {
    RuntimeOptions noSun = options;
    noSun.sun = false;
    std::vector<ShadeResult> full = shadeCpu(set, points, options), ibl = shadeCpu(set, points, noSun);
    std::vector<glm::vec4> out(points.size());
    const LdPyramid& ld = set.distantLd();
    LdChain chain{ld.layout, 0, uint32_t(ld.mapping)};
    for (std::size_t i = 0; i < points.size(); ++i) {
        const ShadingPoint& p = points[i];
        glm::vec3 N = glm::normalize(p.normal), V = glm::normalize(p.view);
        float r = std::clamp(p.perceptualRoughness, 0.0f, 1.0f);
        glm::vec3 R = 2.0f * glm::dot(N, V) * N - V;
        glm::vec3 d = specularDominantDirection(N, R, glm::clamp(glm::dot(N, V), 0.0f, 1.0f), r);
        glm::dvec3 exact = exactLd(environment, d, r);
        glm::dvec3 looked = glm::dvec3(sampleLd(ld.data.data(), chain, vec3(d), r));
        glm::dvec3 specular = glm::dvec3(full[i].specular - ibl[i].specular) +
                              glm::dvec3(ibl[i].specular) * exact / glm::max(looked, glm::dvec3(1e-30));
        out[i] = glm::vec4(glm::vec3(glm::dvec3(full[i].diffuse) + specular), 0.0f);
    }
    return out;
}

struct ColumnErrors {
    std::vector<double> dielectric, metal, both, floor;
    double worst() const { return *std::max_element(both.begin(), both.end()); }
    double mean() const { return std::accumulate(both.begin(), both.end(), 0.0) / double(both.size()); }
};

// Column k's points: the dielectric sphere's, then the metal one's (as many).
std::vector<ShadingPoint> columnPoints(int k) {
    std::vector<ShadingPoint> both = sphereGrid(k / 10.0f, 0.0f, kDielectricBase);
    const std::vector<ShadingPoint> metal = sphereGrid(k / 10.0f, 1.0f, kMetalBase);
    both.insert(both.end(), metal.begin(), metal.end());
    return both;
}

// The reference of every column under `lighting` (default RuntimeOptions): computed once per lighting and
// shared by the probe sets compared with it (it was most of a map's time, and the same for both sets).
using ColumnReferences = std::vector<std::vector<ReferenceResult>>;
ColumnReferences columnReferences(const ReferenceLighting& lighting) {
    ColumnReferences references;
    for (int k = 0; k < kColumns; ++k)
        references.push_back(renderReference(lighting, columnPoints(k), RuntimeOptions{}));
    return references;
}

// Per roughness column: relative mean absolute error (sum |runtime - reference| / sum |reference| over the
// points and RGB) of the dielectric sphere, the metal sphere, and both together (the column), against
// `references` (columnReferences of the lighting); with `environment` (the lighting without the sun, what the
// LD chain holds) also the column's floor.
ColumnErrors sphereGridErrors(const std::string& name, const ProbeSet& set,
                              const ColumnReferences& references, const ReferenceLighting* environment) {
    RuntimeOptions options;
    ColumnErrors errors;
    std::vector<ShadingPoint> all;
    for (int k = 0; k < kColumns; ++k) {
        const std::vector<ShadingPoint> both = columnPoints(k);
        std::vector<glm::vec4> rt = evaluateCpu(set, both, options);
        const std::vector<ReferenceResult>& ref = references[std::size_t(k)];
        std::size_t nd = both.size() / 2;
        errors.dielectric.push_back(relativeError(std::span(rt).first(nd), std::span(ref).first(nd)));
        errors.metal.push_back(relativeError(std::span(rt).subspan(nd), std::span(ref).subspan(nd)));
        errors.both.push_back(relativeError(rt, ref));
        if (environment)
            errors.floor.push_back(relativeError(splitSumWithExactLd(set, *environment, both, options), ref));
        all.insert(all.end(), both.begin(), both.end());
    }
    std::printf("%-50s r:", name.c_str());
    for (int k = 0; k < kColumns; ++k)
        std::printf(" %5.1f", k / 10.0f);
    std::printf("\n");
    const char* rows[4] = {"dielectric", "metal", "column (both)", "column floor: same with exact LD"};
    const std::vector<double>* values[4] = {&errors.dielectric, &errors.metal, &errors.both, &errors.floor};
    for (int row = 0; row < 4; ++row) {
        if (values[row]->empty()) continue;
        std::printf("  %-50s", rows[row]);
        for (double e : *values[row])
            std::printf(" %4.1f%%", 100.0 * e);
        std::printf("\n");
    }
    EXPECT_BACKENDS_AGREE(set, all, options);
    return errors;
}

// Stated tolerances of the sphere grids (lighting the probe set is designed for: a detected sun extracted
// into the disk light). Every column within 20%, the mean of the 11 columns within 10%; columns over 10%
// are listed. Measured limits behind the 20% (see the floor rows): at r = 0.1-0.2 the LD chain's low levels
// (16^2 and 8^2 texels holding lobes narrower than a texel) and the representative-point sun; at r = 1 the
// 1 x 1 top level; and the split sum itself where compact lights remain (studio).
void expectWithinTolerance(const ColumnErrors& e, const std::string& name) {
    for (int k = 0; k < kColumns; ++k) {
        EXPECT_LT(e.both[k], 0.20) << name << " r = " << k / 10.0;
        if (e.both[k] >= 0.10)
            std::printf("  column r = %.1f over 10%%: %.1f%% (floor %.1f%%)\n", k / 10.0, 100 * e.both[k],
                        e.floor.empty() ? 0.0 : 100 * e.floor[k]);
    }
    std::printf("  mean of the columns %.1f%%\n", 100 * e.mean());
    EXPECT_LT(e.mean(), 0.10) << name;
}

TEST(SphereGrid, SyntheticSky) {
    CubeMap sky = makeCube(32, skyLike, 4);
    ReferenceLighting lighting = ReferenceLighting::distant(sky);
    ColumnErrors e =
        sphereGridErrors("synthetic sky (32^2)", distantSet(sky), columnReferences(lighting), &lighting);
    expectWithinTolerance(e, "synthetic sky");
}

const char* kHdris[] = {"rooitou_park_1k.hdr",      "potsdamer_platz_1k.hdr", "studio_small_03_1k.hdr",
                        "venice_sunset_1k.hdr",     "KernerEnvLatLong.exr",   "KernerEnvCube.exr",
                        "blender_world_sunrise.exr"};

// The maps at 64-px faces (a texel of 1.4 degrees: at 32 px the sun's pixels are a bilinear tent 5 degrees
// wide, which no disk reproduces against the full map); compact lights up to 0.02 sr taken out as the disk
// (`--sun-max-solid-angle 0.02`: studio_small_03's softbox, 7e-3 sr, as well as the suns).
constexpr int kHdriFaceSize = 64;
constexpr double kMaxSunSolidAngle = 0.02;

class SphereGridHdri : public ::testing::TestWithParam<const char*> {};

TEST_P(SphereGridHdri, PerColumnErrors) {
    fs::path path = fs::path(IBLBAKE_SHARED_DIR) / "data" / "hdri" / GetParam();
    if (!fs::exists(path)) GTEST_SKIP() << path << " is absent";
    IngestSettings settings;
    settings.sourceFaceSize = kHdriFaceSize;
    CubeMap cube = ingestEnvironment({path}, settings).cube;
    ReferenceLighting whole = ReferenceLighting::distant(cube);
    const ColumnReferences wholeReferences = columnReferences(whole);
    SunDetectSettings sunSettings;
    sunSettings.maxSolidAngle = kMaxSunSolidAngle;
    SunDetection detection = detectSun(cube, sunSettings);
    if (!detection.found) {
        std::printf("(%s: no sun detected: %s)\n", GetParam(), detection.reason.c_str());
        ColumnErrors e = sphereGridErrors(std::string(GetParam()) + ", whole HDRI", distantSet(cube, true),
                                          wholeReferences, &whole);
        expectWithinTolerance(e, GetParam());
        return;
    }
    // 1. The whole HDRI in the probe (LD + SH) against the HDRI: for information. A sun left in the split
    //    sum costs 20-70% on metals (the N = V = R lobe cannot reproduce a compact source's highlight).
    sphereGridErrors(std::string(GetParam()) + ", whole HDRI (sun left in)", distantSet(cube),
                     wholeReferences, nullptr);
    // 2. The sun extracted into the disk light (Frostbite 4.9.1, 4.6), as `iblbake specular --extract-sun`
    //    bakes it: residual in the probe from level 1 on, level 0 the full map; against the full HDRI.
    CubeMap residual = cube;
    DiskLight light = extractSun(residual, detection);
    ProbeSet set = distantSetWithSun(cube, residual, sunDiskFrom(light));
    char label[160];
    std::snprintf(label, sizeof label, "%s, sun extracted (%.2f deg, E %.3g)", GetParam(),
                  light.angularRadius * 57.29578, light.illuminance);
    ReferenceLighting environment = ReferenceLighting::distant(residual);
    ColumnErrors e = sphereGridErrors(label, set, wholeReferences, &environment);
    expectWithinTolerance(e, GetParam());
}

INSTANTIATE_TEST_SUITE_P(Hdri, SphereGridHdri, ::testing::ValuesIn(kHdris), [](const auto& param) {
    std::string s = param.param;
    for (char& c : s)
        if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
    return s;
});

// ------------------------------------------------------------------------------------------------
// Distance-based roughness (Listing 25): a glossy metal floor near a textured wall of a box room, against the
// reference lit by the capture projected onto the proxy.

struct FloorErrors {
    double with = 0.0, without = 0.0;
};

// wallPattern(x) is the radiance of the wall point x (plain floor and ceiling are added here).
template <class Pattern>
std::vector<FloorErrors> glossyFloorErrors(const char* name, Pattern wallPattern,
                                           const std::vector<float>& roughness) {
    const ProbeVolume room = boxVolume(glm::vec3(0, 1.5f, 0), glm::vec3(3, 1.5f, 3));
    const glm::vec3 offset(0.0f, 0.2f, 0.0f);
    const glm::vec3 capturePoint = glm::vec3(room.center) + offset;
    auto radiance = [&](glm::vec3 x) {
        glm::vec3 q = glm::abs((x - glm::vec3(room.center)) / glm::vec3(room.extent));
        if (q.y >= q.x && q.y >= q.z) return x.y > 1.5f ? glm::vec3(1.0f) : glm::vec3(0.2f);
        return wallPattern(x, q.x >= q.z);
    };
    CubeMap capture = makeCube(
        128,
        [&](glm::vec3 d) {
            ParallaxHit h = parallaxCorrect(room, offset, capturePoint, d);
            return radiance(capturePoint + d * h.distanceToHit);
        },
        4);
    ProbeSet set(bakeLd(makeCube(8, [](glm::vec3) { return glm::vec3(0.0f); })), dfgTableFromImage(dfgLut()),
                 ShCoefficients{});
    LocalProbeDesc desc;
    desc.proxy = room;
    desc.captureOffset = offset;
    set.addLocalProbe(desc, bakeLd(capture));
    ReferenceLighting lighting = ReferenceLighting::projected(capture, room, offset);
    const glm::vec3 camera(-1.0f, 1.7f, 0.0f);
    std::printf("glossy metal floor x = 1.5..2.95 m (wall at x = 3 m, capture 3 m away), %s:\n", name);
    std::vector<FloorErrors> out;
    for (float r : roughness) {
        std::vector<ShadingPoint> points;
        for (float x = 1.5f; x < 2.96f; x += 0.05f)
            for (float z = -1.0f; z <= 1.0f; z += 0.1f) {
                glm::vec3 p(x, 1e-3f, z);
                points.push_back(makeShadingPoint(p, glm::vec3(0, 1, 0), glm::normalize(camera - p),
                                                  glm::vec3(1.0f), 1.0f, r));
            }
        RuntimeOptions on, off;
        off.distanceBasedRoughness = false;
        std::vector<ReferenceResult> ref =
            renderReference(lighting, points, on, {.samplesPerStrategy = 4096});
        FloorErrors e{relativeError(evaluateCpu(set, points, on), ref),
                      relativeError(evaluateCpu(set, points, off), ref)};
        std::printf("  r = %.2f: relative error %.1f%% with distance-based roughness, %.1f%% without\n", r,
                    100 * e.with, 100 * e.without);
        EXPECT_BACKENDS_AGREE(set, points, on);
        out.push_back(e);
    }
    return out;
}

TEST(DistanceRoughness, ReducesErrorOnGlossyFloorNearWall) {
    const glm::vec3 dark(0.05f), warm(2.0f, 1.0f, 0.3f), cool(0.3f, 1.0f, 2.0f);
    // Vertical stripes, 0.25 m: the wall's pattern runs along the wall, so the reflection's sharpness (the
    // footprint Listing 25 models) decides the error, not where in height a ray lands.
    std::vector<float> roughness = {0.1f, 0.2f, 0.3f, 0.4f};
    std::vector<FloorErrors> stripes = glossyFloorErrors(
        "vertical stripes 0.25 m",
        [&](glm::vec3 x, bool xWall) {
            int stripe = int(std::floor((xWall ? x.z : x.x) / 0.25f)) & 1;
            return stripe ? (xWall ? warm : cool) : dark;
        },
        roughness);
    for (std::size_t i = 0; i < roughness.size(); ++i)
        EXPECT_LT(stripes[i].with, stripes[i].without) << "r = " << roughness[i];
    // For information: on a checkerboard the reflection's height matters too, and there the listings' other
    // approximations (the lookup direction pulled toward R by r, Appendix F; the dominant direction,
    // probe.h) move it by up to a checker near the wall; a sharper (distance-based) reflection then shows
    // that shift instead of averaging it away, and the comparison goes either way.
    glossyFloorErrors(
        "checkerboard 0.25 m (not asserted)",
        [&](glm::vec3 x, bool xWall) {
            int checker =
                (int(std::floor(x.x / 0.25f)) + int(std::floor(x.y / 0.25f)) + int(std::floor(x.z / 0.25f))) &
                1;
            return checker ? (xWall ? warm : cool) : dark;
        },
        roughness);
}

// ------------------------------------------------------------------------------------------------
// The sun as a disk light against the reference's uniform disk: black environment, so only the light is
// measured (Listing 6's punctual diffuse; specular by the disk quadrature, and Listing 6's representative
// point normalized and as printed, for comparison).

TEST(Sun, DiskLightAgainstUniformDisk) {
    CubeMap black = makeCube(8, [](glm::vec3) { return glm::vec3(0.0f); });
    ProbeSet set = distantSet(black);
    // The real sun: 0.53 deg across (Frostbite footnote 28); a mid-morning direction.
    SunDisk sun{glm::normalize(glm::vec3(-0.4f, 0.7f, 0.5f)), 0.00465f, glm::vec3(1.0f, 0.96f, 0.9f), 1.0f};
    RuntimeOptions options, point = options, listing = options;
    point.sunQuadrature = false;
    listing.sunQuadrature = false;
    listing.sunEnergyNormalization = false;
    RuntimeOptions diffuseOnly = options;
    diffuseOnly.specular = false;
    std::printf("sun only: relative error per roughness (r = 0 is left out: a grid point either catches the "
                "mirror image of the disk or does not)\n");
    // The real sun (0.53 deg across) and the disks extracted from 32-px maps (about 1.6 deg in radius).
    for (float radius : {0.00465f, 0.028f}) {
        sun.angularRadius = radius;
        set.setSun(sun);
        ReferenceLighting lighting = ReferenceLighting::distant(black, sun);
        std::printf(" disk radius %.2f deg\n", radius * 57.29578f);
        for (int k = 1; k < kColumns; ++k) {
            float r = k / 10.0f;
            std::vector<ShadingPoint> dielectric = sphereGrid(r, 0.0f, kDielectricBase);
            std::vector<ShadingPoint> metal = sphereGrid(r, 1.0f, kMetalBase);
            double eDiffuse = relativeError(evaluateCpu(set, dielectric, diffuseOnly),
                                            renderReference(lighting, dielectric, diffuseOnly));
            std::vector<ReferenceResult> refMetal = renderReference(lighting, metal, options);
            double eMetal = relativeError(evaluateCpu(set, metal, options), refMetal);
            double ePoint = relativeError(evaluateCpu(set, metal, point), refMetal);
            double eListing = relativeError(evaluateCpu(set, metal, listing), refMetal);
            std::printf(
                "  r = %.1f: diffuse %.2f%%, metal %.2f%% (representative point, normalized %.1f%%, as "
                "printed %.1f%%)\n",
                r, 100 * eDiffuse, 100 * eMetal, 100 * ePoint, 100 * eListing);
            EXPECT_LT(eDiffuse, radius < 0.01f ? 0.01 : 0.02) << "punctual diffuse, r = " << r;
            // 32 points: 0.4% (real sun) and 3.3% (1.6 deg disk) at r = 0.1, below 1% from r = 0.2 on.
            EXPECT_LT(eMetal, r < 0.15f ? 0.05 : 0.01) << "disk quadrature, r = " << r;
            EXPECT_BACKENDS_AGREE(set, metal, options);
        }
    }
}

} // namespace
