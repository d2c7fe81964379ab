// Sun detection, measurement and extraction (iblbake/baker/sun.h): synthetic environments with a known sun,
// environments without one, and the shared HDRIs (SOURCES.md).
//
// Tolerances: synthetic one-texel suns on a flat sky are recovered to 1e-5 (the fill of a constant boundary
// is that constant, so only float storage rounds); a sun spread over several texels on a sloping sky to
// 0.5 % (the membrane fill of a curved sky is not exact); directions on the shared HDRIs within 1 degree of
// the brightest pixel (the disk is 0.53 degrees, a 1k pixel 0.35); energy removed == E_perp to 0.5 % (it is
// equal by construction; the test recomputes it independently from the two images).
#include "iblbake/baker/calibration.h"
#include "iblbake/baker/environment_stats.h"
#include "iblbake/baker/ingest.h"
#include "iblbake/baker/sun.h"
#include "iblbake/core/error.h"

#include <cube.h>

#include "sphere_texels_support.h"
#include <OpenImageIO/imageio.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <functional>
#include <iostream>
#include <numbers>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;
using namespace ibl;
using ibl::test::cubeOf;
using ibl::test::latLongOf;

constexpr double kPi = std::numbers::pi;
constexpr double kDeg = kPi / 180.0;

double angleDegrees(const glm::dvec3& a, const glm::dvec3& b) {
    return std::atan2(glm::length(glm::cross(a, b)), glm::dot(a, b)) / kDeg;
}

double lum(const glm::dvec3& c) {
    return glm::dot(kRec709Luminance, c);
}

std::size_t cubeIndex(int n, int face, int i, int j) {
    return (std::size_t(face) * n + std::size_t(j)) * n + std::size_t(i);
}

// Adds `energy` (luminance times solid angle) of colour `rgb` (luminance 1) to texel k.
void addEnergy(SphereTexels& t, std::size_t k, double energy, const glm::dvec3& rgb) {
    t.setRgb(k, t.rgb(k) + glm::vec3(rgb * (energy / t.solidAngle(k))));
}

glm::dvec3 totalEnergy(const SphereTexels& t) {
    glm::dvec3 e(0.0);
    for (std::size_t i = 0; i < t.size(); ++i)
        e += glm::dvec3(t.rgb(i)) * t.solidAngle(i);
    return e;
}

// Residual checks after extraction: finite, non-negative, nothing above the threshold near the sun.
void expectCleanResidual(const SphereTexels& t, const SunDetection& det, const glm::dvec3& sunDir) {
    std::size_t bad = 0, bright = 0;
    for (std::size_t i = 0; i < t.size(); ++i) {
        const glm::vec3 c = t.rgb(i);
        if (!(std::isfinite(c.x) && std::isfinite(c.y) && std::isfinite(c.z)) || c.x < 0 || c.y < 0 ||
            c.z < 0)
            ++bad;
        if (angleDegrees(t.direction(i), sunDir) < 10.0 && lum(glm::dvec3(c)) > det.threshold) ++bright;
    }
    EXPECT_EQ(bad, 0u) << "NaN, Inf or negative texels in the residual";
    EXPECT_EQ(bright, 0u) << "texels above the detection threshold within 10 degrees of the sun";
}

// ---------------------------------------------------------------------------------------------------
// Synthetic suns

TEST(Sun, OneTexelSunOnFlatSkyIsRecoveredExactly) {
    const int n = 64;
    CubeMap cube = cubeOf(n, [](const glm::dvec3&) { return glm::vec3(0.5f); });
    SphereTexels t(cube);
    const glm::dvec3 rgb = glm::dvec3(1.2, 0.98, 0.7) / lum(glm::dvec3(1.2, 0.98, 0.7));
    const std::size_t k = cubeIndex(n, 4, 20, 25);
    const double energy = 2.0;
    addEnergy(t, k, energy, rgb);
    const glm::dvec3 before = totalEnergy(t);

    const SunDetection det = detectSun(t);
    ASSERT_TRUE(det.found) << det.reason;
    EXPECT_NEAR(det.light.illuminance, energy, 1e-5 * energy);
    EXPECT_LT(angleDegrees(det.light.direction, t.direction(k)), 1e-4);
    for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(det.light.color[c], rgb[c], 1e-4) << c;
    // A one-texel light is the disk of its texel's solid angle.
    EXPECT_NEAR(det.light.angularRadius, std::sqrt(t.solidAngle(k) / kPi), 1e-3 * det.light.angularRadius);
    EXPECT_NEAR(det.skyLuminance, 0.5, 1e-6);
    EXPECT_NEAR(det.surroundLuminance, 0.5, 1e-6);

    const DiskLight light = extractSun(t, det);
    EXPECT_NEAR(light.illuminance, energy, 1e-5 * energy);
    // The flat sky comes back everywhere.
    for (std::size_t i = 0; i < t.size(); ++i)
        ASSERT_NEAR(lum(glm::dvec3(t.rgb(i))), 0.5, 1e-5) << i;
    EXPECT_NEAR(lum(before - totalEnergy(t)), light.illuminance, 1e-4 * light.illuminance);
}

TEST(Sun, SpreadSunAcrossACubeEdgeOnSlopingSky) {
    // The sun straddles the edge between +Z (face 4) and +X (face 0): energy split over four texels on two
    // faces, on a sky that brightens toward the zenith. Neighbourhoods must cross the edge.
    const int n = 128;
    auto sky = [](const glm::dvec3& d) { return glm::vec3(float(0.4 + 0.3 * d.y + 0.1 * d.x)); };
    CubeMap cube = cubeOf(n, sky);
    SphereTexels t(cube);
    const glm::dvec3 white(1.0);
    // +Z's last column (i = n-1) touches +X's first column (i = 0) on the same rows.
    const std::size_t texels[4] = {cubeIndex(n, 4, n - 1, 50), cubeIndex(n, 0, 0, 50),
                                   cubeIndex(n, 4, n - 1, 51), cubeIndex(n, 0, 0, 51)};
    const double share[4] = {0.4, 0.3, 0.2, 0.1};
    const double energy = 0.5;
    glm::dvec3 centroid(0.0);
    for (int k = 0; k < 4; ++k) {
        addEnergy(t, texels[k], energy * share[k], white);
        centroid += energy * share[k] * t.direction(texels[k]);
    }
    const SunDetection det = detectSun(t);
    ASSERT_TRUE(det.found) << det.reason;
    EXPECT_NEAR(det.light.illuminance, energy, 0.005 * energy);
    EXPECT_LT(angleDegrees(det.light.direction, glm::normalize(centroid)), 0.05);
    const glm::dvec3 before = totalEnergy(t);
    const DiskLight light = extractSun(t, det);
    EXPECT_NEAR(lum(before - totalEnergy(t)), light.illuminance, 0.005 * light.illuminance);
    expectCleanResidual(t, det, light.direction);
    EXPECT_FALSE(detectSun(t).found);
}

TEST(Sun, LatLongSunNextToThePole) {
    // A sun in the second row of a lat-long: its neighbourhood wraps over the pole.
    const int w = 256, h = 128;
    ImageRGBA im = latLongOf(w, h, [](const glm::dvec3&) { return glm::vec3(1.0f); });
    SphereTexels t(im, LatLongPixels::Centre);
    const std::size_t k = std::size_t(1) * w + 17;
    addEnergy(t, k, 0.2, glm::dvec3(1.0));
    const SunDetection det = detectSun(t);
    ASSERT_TRUE(det.found) << det.reason;
    EXPECT_NEAR(det.light.illuminance, 0.2, 1e-5 * 0.2);
    EXPECT_LT(angleDegrees(det.light.direction, t.direction(k)), 1e-4);
    extractSun(t, det);
    for (std::size_t i = 0; i < t.size(); ++i)
        ASSERT_NEAR(lum(glm::dvec3(t.rgb(i))), 1.0, 1e-5) << i;
}

// The sky level is the upper hemisphere's solid-angle-weighted median, found from per-bin weights and the
// one bin where half is crossed: it must be the value a full sort and running sum finds, on skies of many
// distinct values at an odd and an even face size (a bin search that lost a part of the range, or the
// weight before it, would land elsewhere) and on a real HDRI (many equal values, a sun).
void expectSortedWeightedMedian(const CubeMap& cube, const std::string& label) {
    const SphereTexels texels(cube);
    std::vector<std::pair<float, double>> upper;
    for (std::size_t i = 0; i < texels.size(); ++i)
        if (texels.vectorSolidAngle(i).y > 0.0)
            upper.emplace_back(float(lum(glm::dvec3(texels.rgb(i)))), texels.solidAngle(i));
    std::sort(upper.begin(), upper.end());
    double total = 0.0, acc = 0.0;
    for (const auto& sample : upper)
        total += sample.second;
    double median = upper.back().first;
    for (const auto& [value, weight] : upper)
        if ((acc += weight) >= 0.5 * total) {
            median = value;
            break;
        }
    EXPECT_EQ(detectSun(cube, SunDetectSettings{}).skyLuminance, median) << label;
}

TEST(Sun, SkyLevelIsTheSortedWeightedMedian) {
    for (int n : {31, 64})
        expectSortedWeightedMedian(
            cubeOf(n,
                   [](const glm::dvec3& d) {
                       return glm::vec3(
                           float(1.0 + std::sin(7.0 * d.x) * std::cos(5.0 * d.z) + 2.0 * d.y * d.y));
                   }),
            "face size " + std::to_string(n));
    expectSortedWeightedMedian(
        ingestEnvironment({fs::path(IBLBAKE_SOURCE_DIR) / "data" / "rooitou_park_1k.hdr"}, {}).cube,
        "the sample HDRI");
}

TEST(Sun, NoSunWhereThereIsNone) {
    const int n = 64;
    // Black, flat, and an overcast-like smooth sky.
    EXPECT_FALSE(detectSun(cubeOf(n, [](const glm::dvec3&) { return glm::vec3(0.0f); })).found);
    EXPECT_FALSE(detectSun(cubeOf(n, [](const glm::dvec3&) { return glm::vec3(3.0f); })).found);
    const SunDetection overcast = detectSun(
        cubeOf(n, [](const glm::dvec3& d) { return glm::vec3(float(1.0 + 2.0 * std::max(0.0, d.y))); }));
    EXPECT_FALSE(overcast.found);
    EXPECT_NE(overcast.reason.find("times its surroundings"), std::string::npos) << overcast.reason;

    // A large area light: a 6-degree cap, 1000 times the room.
    const glm::dvec3 axis = glm::normalize(glm::dvec3(1, 1, 0.3));
    const SunDetection area = detectSun(cubeOf(
        128, [&](const glm::dvec3& d) { return glm::vec3(angleDegrees(d, axis) < 6.0 ? 1000.0f : 1.0f); }));
    EXPECT_FALSE(area.found);
    EXPECT_NE(area.reason.find("larger than"), std::string::npos) << area.reason;

    // Three equally bright small lights: none dominates.
    CubeMap three = cubeOf(n, [](const glm::dvec3&) { return glm::vec3(0.1f); });
    SphereTexels t(three);
    for (int face : {0, 2, 4})
        addEnergy(t, cubeIndex(n, face, 30, 30), 1.0, glm::dvec3(1.0));
    const SunDetection several = detectSun(t);
    EXPECT_FALSE(several.found);
    EXPECT_NE(several.reason.find("several"), std::string::npos) << several.reason;

    // A compact spot, but faint: 4 stops over the sky (above the threshold) in one texel of 2.4e-4 sr
    // carries a fiftieth of the light a sun would.
    CubeMap faint = cubeOf(128, [](const glm::dvec3&) { return glm::vec3(1.0f); });
    SphereTexels f(faint);
    f.setRgb(cubeIndex(128, 4, 60, 60), glm::vec3(20.0f));
    const SunDetection spot = detectSun(f);
    EXPECT_FALSE(spot.found);
    EXPECT_NE(spot.reason.find("as bright as its surroundings"), std::string::npos) << spot.reason;

    // Two equal suns: neither dominates.
    CubeMap two = cubeOf(n, [](const glm::dvec3&) { return glm::vec3(0.1f); });
    SphereTexels t2(two);
    addEnergy(t2, cubeIndex(n, 0, 10, 10), 1.0, glm::dvec3(1.0));
    addEnergy(t2, cubeIndex(n, 1, 10, 10), 1.0, glm::dvec3(1.0)); // same solid angle: exactly half each
    EXPECT_FALSE(detectSun(t2).found);
}

TEST(Sun, ExtractionNeedsADetection) {
    CubeMap cube = cubeOf(16, [](const glm::dvec3&) { return glm::vec3(1.0f); });
    SunDetection none;
    EXPECT_THROW(extractSun(cube, none), Error);
    SunDetection wrong;
    wrong.found = true;
    wrong.region = {999999};
    wrong.fill = {glm::vec3(0.0f)};
    wrong.texelCount = 6 * 16 * 16;
    EXPECT_THROW(extractSun(cube, wrong), Error);
    // Found on another grid (a 32 cube), applied to this one.
    CubeMap big = cubeOf(32, [](const glm::dvec3&) { return glm::vec3(0.1f); });
    SphereTexels b(big);
    b.setRgb(100, glm::vec3(5000.0f));
    const SunDetection other = detectSun(big);
    ASSERT_TRUE(other.found) << other.reason;
    EXPECT_THROW(extractSun(cube, other), Error);
    const CubeMap& constCube = cube;
    SphereTexels readOnly(constCube);
    EXPECT_FALSE(readOnly.writable());
    EXPECT_THROW(readOnly.setRgb(0, glm::vec3(1.0f)), Error);
}

TEST(Sun, DiskLightJsonRoundTrip) {
    DiskLight l;
    l.direction = glm::normalize(glm::dvec3(-0.58, 0.18, 0.79));
    l.angularRadius = 0.4 * kDeg;
    l.color = glm::dvec3(1.09, 1.01, 0.61);
    l.illuminance = 104567.25;
    l.solidAngle = 8.5e-4;
    const std::string json = diskLightToJson(l, true);
    EXPECT_NE(json.find("\"illuminanceLux\""), std::string::npos);
    EXPECT_NE(json.find("\"units\": \"lux\""), std::string::npos);
    const DiskLight r = diskLightFromJson(json);
    EXPECT_LT(angleDegrees(r.direction, l.direction), 1e-9);
    EXPECT_NEAR(r.angularRadius, l.angularRadius, 1e-12);
    EXPECT_DOUBLE_EQ(r.illuminance, l.illuminance);
    EXPECT_DOUBLE_EQ(r.solidAngle, l.solidAngle);
    for (int c = 0; c < 3; ++c)
        EXPECT_DOUBLE_EQ(r.color[c], l.color[c]);
    EXPECT_NEAR(r.elevationDegrees(), l.elevationDegrees(), 1e-9);
    EXPECT_THROW(diskLightFromJson("{\"type\": \"disk\"}"), Error);
    EXPECT_THROW(diskLightFromJson("not json"), Error);
}

// ---------------------------------------------------------------------------------------------------
// Shared HDRIs

const fs::path kHdri = fs::path(IBLBAKE_SHARED_DIR) / "data" / "hdri";

#define REQUIRE_SHARED(name)                                                                                 \
    do {                                                                                                     \
        if (!fs::exists(kHdri / (name))) GTEST_SKIP() << (kHdri / (name)).string() << " is not present";     \
    } while (0)

struct Peak {
    int x = 0, y = 0;
    double luminance = 0.0;
    glm::dvec3 direction;
};

// The brightest pixel of a lat-long file, read here with OIIO, and its direction: the docs/conventions.md
// mapping of its centre in the placement's grid (latlong_pixels.h; SOURCES.md's notes use pixel centres).
Peak brightestPixel(const fs::path& file, LatLongPixels placement) {
    auto in = OIIO::ImageInput::open(file.string());
    EXPECT_TRUE(in) << OIIO::geterror();
    Peak p;
    if (!in) return p;
    const OIIO::ImageSpec spec = in->spec();
    std::vector<float> px(std::size_t(spec.width) * spec.height * spec.nchannels);
    EXPECT_TRUE(in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, px.data()));
    for (int y = 0; y < spec.height; ++y)
        for (int x = 0; x < spec.width; ++x) {
            const float* c = &px[(std::size_t(y) * spec.width + x) * spec.nchannels];
            const double l = 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2];
            if (l > p.luminance) p = {x, y, l, glm::dvec3(0.0)};
        }
    p.direction = glm::dvec3(directionFromLatlong(float(latLongPixelCentre(placement, p.x, spec.width)),
                                                  float(latLongPixelCentre(placement, p.y, spec.height))));
    return p;
}

struct SunCase {
    const char* file;
    int peakX, peakY; // SOURCES.md
};

class SharedSun : public ::testing::TestWithParam<SunCase> {};

TEST_P(SharedSun, FoundAtTheBrightestPixelAndExtractedExactly) {
    const SunCase c = GetParam();
    REQUIRE_SHARED(c.file);
    const fs::path file = kHdri / c.file;
    SourceEnvironment env = ingestEnvironment({file}, {});
    ASSERT_TRUE(env.report.latLongPixels);
    const LatLongPixels placement = *env.report.latLongPixels;
    const Peak peak = brightestPixel(file, placement);
    EXPECT_EQ(peak.x, c.peakX);
    EXPECT_EQ(peak.y, c.peakY);

    ImageRGBA latlong = readWorkingLatLong(file, {});
    const EnvironmentStats stats = computeEnvironmentStats(env.cube);
    double cubeE = 0.0;
    for (int grid = 0; grid < 2; ++grid) {
        SphereTexels t = grid == 0 ? SphereTexels(env.cube) : SphereTexels(latlong, placement);
        const char* gridName = grid == 0 ? "cube" : "latlong";
        const SunDetection det = detectSun(t);
        ASSERT_TRUE(det.found) << gridName << ": " << det.reason;
        const DiskLight& l = det.light;
        EXPECT_LT(angleDegrees(l.direction, peak.direction), 1.0) << gridName;
        EXPECT_LT(l.solidAngle, 3e-3) << gridName;
        EXPECT_GT(l.angularRadius, 0.1 * kDeg);
        EXPECT_LT(l.angularRadius, 1.0 * kDeg);
        EXPECT_GE(std::min({l.color.x, l.color.y, l.color.z}), 0.0);
        EXPECT_NEAR(lum(l.color), 1.0, 1e-9);

        const glm::dvec3 before = totalEnergy(t);
        const DiskLight light = extractSun(t, det);
        const double removed = lum(before - totalEnergy(t));
        EXPECT_NEAR(removed, light.illuminance, 0.005 * light.illuminance) << gridName;
        EXPECT_NEAR(light.illuminance, l.illuminance, 1e-9 * l.illuminance) << gridName;
        expectCleanResidual(t, det, light.direction);
        const SunDetection again = detectSun(t);
        EXPECT_FALSE(again.found) << gridName << ": a second sun after extraction";

        if (grid == 0)
            cubeE = light.illuminance;
        else
            EXPECT_NEAR(light.illuminance, cubeE, 0.01 * cubeE) << "lat-long and cube disagree";
        std::cout << c.file << " [" << gridName << "] sun elevation " << light.elevationDegrees()
                  << " deg, azimuth " << light.azimuthDegrees() << " deg, offset from peak pixel "
                  << angleDegrees(light.direction, peak.direction) << " deg, E_perp " << light.illuminance
                  << ", solid angle " << light.solidAngle << " sr, radius " << light.angularRadius / kDeg
                  << " deg, energy error " << (removed - light.illuminance) / light.illuminance
                  << "; upward E " << stats.upwardIlluminance << ", EV100 " << stats.ev100 << "\n";
    }
}

INSTANTIATE_TEST_SUITE_P(Hdri, SharedSun,
                         ::testing::Values(SunCase{"rooitou_park_1k.hdr", 614, 226},
                                           SunCase{"venice_sunset_1k.hdr", 614, 246},
                                           SunCase{"blender_world_sunrise.exr", 613, 233}),
                         [](const ::testing::TestParamInfo<SunCase>& p) {
                             std::string name = p.param.file;
                             return name.substr(0, name.find('_'));
                         });

class SharedNoSun : public ::testing::TestWithParam<const char*> {};

TEST_P(SharedNoSun, ReportsNoSun) {
    REQUIRE_SHARED(GetParam());
    const fs::path file = kHdri / GetParam();
    const SourceEnvironment env = ingestEnvironment({file}, {});
    const SunDetection cube = detectSun(env.cube);
    EXPECT_FALSE(cube.found) << "cube: sun at elevation " << cube.light.elevationDegrees();
    EXPECT_FALSE(cube.reason.empty());
    IngestReport report;
    const ImageRGBA latlong = readWorkingLatLong(file, {}, &report);
    const SunDetection ll = detectSun(SphereTexels(latlong, *report.latLongPixels));
    EXPECT_FALSE(ll.found) << "latlong: sun at elevation " << ll.light.elevationDegrees();
    std::cout << GetParam() << ": no sun: " << cube.reason << "\n";
}

INSTANTIATE_TEST_SUITE_P(Hdri, SharedNoSun,
                         ::testing::Values("potsdamer_platz_1k.hdr", "studio_small_03_1k.hdr"),
                         [](const ::testing::TestParamInfo<const char*>& p) {
                             std::string name = p.param;
                             return name.substr(0, name.find('_'));
                         });

TEST(SharedSunCube, KernerCubeAndLatLongAgree) {
    REQUIRE_SHARED("KernerEnvCube.exr");
    REQUIRE_SHARED("KernerEnvLatLong.exr");
    // SOURCES.md: the peak is the direction (-0.899, 0.352, 0.262) in both files.
    const glm::dvec3 peak = glm::normalize(glm::dvec3(-0.899, 0.352, 0.262));
    const SunDetection cube = detectSun(ingestEnvironment({kHdri / "KernerEnvCube.exr"}, {}).cube);
    const SunDetection ll = detectSun(ingestEnvironment({kHdri / "KernerEnvLatLong.exr"}, {}).cube);
    ASSERT_TRUE(cube.found) << cube.reason;
    ASSERT_TRUE(ll.found) << ll.reason;
    EXPECT_LT(angleDegrees(cube.light.direction, peak), 1.0);
    EXPECT_LT(angleDegrees(ll.light.direction, peak), 1.0);
    EXPECT_NEAR(cube.light.illuminance, ll.light.illuminance, 0.02 * ll.light.illuminance);
}

} // namespace
