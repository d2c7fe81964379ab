// Lat-long pixel placement (docs/conventions.md "Lat-long mapping and pixel placement", latlong_pixels.h): a
// Poly Haven map ingests as pixel centres, checked against an integration over its pixels written here
// independently of the baker; a file carrying OpenEXR's envmap attribute keeps OpenEXR's placement; the
// override works both ways; the placement is recorded in the products of a bake and bad values name their
// flag or scene key.
#include "cli_runner.h"
#include "scene_test_support.h"

#include "iblbake/baker/calibration.h"
#include "iblbake/baker/ingest.h"
#include "iblbake/baker/sh.h"
#include "iblbake/baker/sun.h"
#include "iblbake/core/error.h"
#include "iblbake/ktx2/ktx2.h"

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <numbers>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using namespace ibl;
using namespace ibl::test;
using nlohmann::json;

namespace {

constexpr double kPi = std::numbers::pi;

const fs::path kShared = fs::path(IBLBAKE_SHARED_DIR) / "data";

#define REQUIRE_FILE(p)                                                                                      \
    do {                                                                                                     \
        if (!fs::exists(p)) GTEST_SKIP() << (p) << " not present";                                           \
    } while (0)

// The file's R, G, B, read here with OIIO (no colour conversion: a Radiance file is linear Rec.709, the
// working space).
struct Pixels {
    int width = 0, height = 0;
    std::vector<float> rgb;
};

Pixels readRgb(const fs::path& file) {
    Pixels p;
    auto in = OIIO::ImageInput::open(file.string());
    EXPECT_TRUE(in) << OIIO::geterror();
    if (!in) return p;
    p.width = in->spec().width;
    p.height = in->spec().height;
    p.rgb.resize(std::size_t(p.width) * p.height * 3);
    EXPECT_TRUE(in->read_image(0, 0, 0, 3, OIIO::TypeDesc::FLOAT, p.rgb.data()));
    return p;
}

// ---- the independent pixel-centre integration (not the baker's code) ----
// Pixel (x, y) of a W x H lat-long covers u in [x/W, (x+1)/W], v in [y/H, (y+1)/H]; it looks along its
// centre u = (x+0.5)/W, v = (y+0.5)/H; longitude = (0.5 - u) 2 pi, latitude = (0.5 - v) pi
// (docs/conventions.md: longitude = atan2(d.x, d.z), latitude = asin(d.y)); its solid angle is exactly (2 pi
// / W) (cos(pi y / H) - cos(pi (y+1) / H)) (the colatitude of its top and bottom edges).
double centrePixelSolidAngle(int y, int w, int h) {
    return 2.0 * kPi / w * (std::cos(kPi * y / h) - std::cos(kPi * (y + 1) / h));
}

glm::dvec3 centrePixelDirection(int x, int y, int w, int h) {
    const double longitude = (0.5 - (x + 0.5) / w) * 2.0 * kPi, latitude = (0.5 - (y + 0.5) / h) * kPi;
    return {std::cos(latitude) * std::sin(longitude), std::sin(latitude),
            std::cos(latitude) * std::cos(longitude)};
}

// Real L2 SH, standard normalization, docs/conventions.md order.
std::array<double, 9> shBasis(const glm::dvec3& d) {
    const double x = d.x, y = d.y, z = d.z;
    return {0.28209479177387814,
            0.4886025119029199 * y,
            0.4886025119029199 * z,
            0.4886025119029199 * x,
            1.0925484305920792 * x * y,
            1.0925484305920792 * y * z,
            0.31539156525252005 * (3.0 * z * z - 1.0),
            1.0925484305920792 * x * z,
            0.5462742152960396 * (x * x - y * y)};
}

// Radiance projection: sum over pixels of L Y_i(centre) omega.
std::array<glm::dvec3, 9> centreProjection(const Pixels& p) {
    std::array<glm::dvec3, 9> sh{};
    for (int y = 0; y < p.height; ++y) {
        const double omega = centrePixelSolidAngle(y, p.width, p.height);
        for (int x = 0; x < p.width; ++x) {
            const float* c = &p.rgb[(std::size_t(y) * p.width + x) * 3];
            const std::array<double, 9> b = shBasis(centrePixelDirection(x, y, p.width, p.height));
            for (int i = 0; i < 9; ++i)
                sh[std::size_t(i)] += glm::dvec3(c[0], c[1], c[2]) * (b[std::size_t(i)] * omega);
        }
    }
    return sh;
}

// The largest relative difference of a coefficient, over the coefficients that carry at least a tenth of
// their channel's coefficient-vector length (the others are near zero, where a relative error means
// nothing), worst channel.
double shDifference(const ShRgb& got, const std::array<glm::dvec3, 9>& reference) {
    double worst = 0.0;
    for (int c = 0; c < 3; ++c) {
        double norm = 0.0;
        for (int i = 0; i < 9; ++i)
            norm += reference[std::size_t(i)][c] * reference[std::size_t(i)][c];
        for (int i = 0; i < 9; ++i) {
            const double r = reference[std::size_t(i)][c];
            if (std::fabs(r) >= 0.1 * std::sqrt(norm))
                worst = std::max(worst, std::fabs(got[std::size_t(i)][c] / r - 1.0));
        }
    }
    return worst;
}

IngestSettings withPlacement(LatLongPixels placement) {
    IngestSettings s;
    s.latLongPixels = placement;
    return s;
}

// The solid angle of a detected sun's region of lat-long pixels, summed here from the pixel-centre grid.
double centreRegionSolidAngle(const SunDetection& det, int w, int h) {
    double omega = 0.0;
    for (std::size_t i : det.region)
        omega += centrePixelSolidAngle(int(i / std::size_t(w)), w, h);
    return omega;
}

std::string keyValue(const fs::path& ktx2, const std::string& key) {
    const Ktx2Image image = readKtx2(ktx2);
    const auto it = image.keyValues.find(key);
    return it == image.keyValues.end() ? std::string("(absent)") : it->second;
}

bool sameCube(const CubeMap& a, const CubeMap& b) {
    if (a.faceSize != b.faceSize) return false;
    for (std::size_t f = 0; f < 6; ++f)
        if (a.faces[f].pixels != b.faces[f].pixels) return false;
    return true;
}

json readJson(const fs::path& file) {
    return json::parse(readBytes(file));
}

} // namespace

// rooitou_park: the set's strong-sun Poly Haven map (SOURCES.md; the set has no noon map, its sun is 10.4
// degrees above the horizon). The 0.2 % of the issue: ingest (auto = pixel centres for a Radiance file)
// and the SH projected from its 512-texel source cube match the direct sum over the file's pixels; the
// detected sun's solid angle, on the lat-long's own pixels, matches the sum of the exact pixel-centre solid
// angles of its region. OpenEXR's placement moves both by more than that.
TEST(LatLongPixels, PolyHavenMapMatchesAnIndependentPixelCentreIntegration) {
    const fs::path file = kShared / "hdri" / "rooitou_park_1k.hdr";
    REQUIRE_FILE(file);
    const Pixels pixels = readRgb(file);
    ASSERT_EQ(pixels.width, 1024);
    const std::array<glm::dvec3, 9> reference = centreProjection(pixels);

    IngestSettings autoSettings;
    autoSettings.sourceFaceSize = 512;
    IngestSettings openExrSettings = autoSettings;
    openExrSettings.latLongPixels = LatLongPixels::OpenExr;
    const SourceEnvironment centre = ingestEnvironment({file}, autoSettings);
    ASSERT_EQ(centre.report.latLongPixels, LatLongPixels::Centre);
    const double centreSh = shDifference(projectRadianceSH(centre.cube), reference);
    const double openExrSh =
        shDifference(projectRadianceSH(ingestEnvironment({file}, openExrSettings).cube), reference);
    EXPECT_LT(centreSh, 0.002);
    EXPECT_GT(openExrSh, 0.002);

    // The sun, detected on the lat-long's own pixels in each placement.
    IngestReport report;
    const ImageRGBA latlong = readWorkingLatLong(file, {}, &report);
    ASSERT_EQ(report.latLongPixels, LatLongPixels::Centre);
    const SunDetection sunCentre = detectSun(SphereTexels(latlong, LatLongPixels::Centre));
    const SunDetection sunOpenExr = detectSun(SphereTexels(latlong, LatLongPixels::OpenExr));
    ASSERT_TRUE(sunCentre.found) << sunCentre.reason;
    ASSERT_TRUE(sunOpenExr.found) << sunOpenExr.reason;
    const double independent = centreRegionSolidAngle(sunCentre, pixels.width, pixels.height);
    const double centreSun = std::fabs(sunCentre.light.solidAngle / independent - 1.0);
    const double openExrSun = std::fabs(
        sunOpenExr.light.solidAngle / centreRegionSolidAngle(sunOpenExr, pixels.width, pixels.height) - 1.0);
    EXPECT_LT(centreSun, 0.002);
    EXPECT_GT(openExrSun, 0.002);

    // The production path: the sun detected on the source cube, E_perp in both placements.
    const SunDetection cubeCentre = detectSun(centre.cube);
    const SunDetection cubeOpenExr = detectSun(ingestEnvironment({file}, openExrSettings).cube);
    ASSERT_TRUE(cubeCentre.found && cubeOpenExr.found);
    std::cout << "SH vs independent pixel-centre sum: centre " << centreSh << ", openexr " << openExrSh
              << "\nsun solid angle vs independent: centre " << centreSun << ", openexr " << openExrSun
              << " (region " << sunCentre.region.size() << " / " << sunOpenExr.region.size() << " px, "
              << independent << " sr)\nsun on the cube: E_perp openexr/centre "
              << cubeOpenExr.light.illuminance / cubeCentre.light.illuminance << ", solid angle "
              << cubeOpenExr.light.solidAngle / cubeCentre.light.solidAngle << "\n";
    RecordProperty("sh_centre", std::to_string(centreSh));
    RecordProperty("sh_openexr", std::to_string(openExrSh));
    RecordProperty("sun_solid_angle_centre", std::to_string(centreSun));
    RecordProperty("sun_solid_angle_openexr", std::to_string(openExrSun));
}

// A file with envmap = latlong keeps OpenEXR's placement under auto (and so ingests as it did before pixel
// centres became the default); the labelled orientation pair still ingests to the same cube (checked in
// test_ingest.cpp IngestShared.*).
TEST(LatLongPixels, OpenExrEnvmapFileKeepsOpenExrPlacement) {
    const fs::path file = kShared / "orientation" / "OrientationLatLong.exr";
    REQUIRE_FILE(file);
    IngestSettings s = withPlacement(LatLongPixels::Auto);
    s.sourceFaceSize = 32;
    const SourceEnvironment autoEnv = ingestEnvironment({file}, s);
    ASSERT_EQ(autoEnv.report.latLongPixels, LatLongPixels::OpenExr);
    s.latLongPixels = LatLongPixels::OpenExr;
    const SourceEnvironment openExr = ingestEnvironment({file}, s);
    s.latLongPixels = LatLongPixels::Centre;
    const SourceEnvironment centre = ingestEnvironment({file}, s);
    EXPECT_EQ(centre.report.latLongPixels, LatLongPixels::Centre); // the override, this way
    EXPECT_TRUE(sameCube(autoEnv.cube, openExr.cube));
    EXPECT_FALSE(sameCube(autoEnv.cube, centre.cube));
}

TEST(LatLongPixels, OverrideWorksBothWaysAndCubesHaveNone) {
    const fs::path dir = freshTempDir("latlong_override");
    writeLatLong(dir / "sky.exr", 0.5f); // no envmap attribute: pixel centres
    IngestSettings s;
    s.sourceFaceSize = 8;
    const SourceEnvironment autoEnv = ingestEnvironment({dir / "sky.exr"}, s);
    EXPECT_EQ(autoEnv.report.latLongPixels, LatLongPixels::Centre);
    s.latLongPixels = LatLongPixels::OpenExr;
    const SourceEnvironment openExr = ingestEnvironment({dir / "sky.exr"}, s);
    EXPECT_EQ(openExr.report.latLongPixels, LatLongPixels::OpenExr);
    EXPECT_FALSE(sameCube(autoEnv.cube, openExr.cube));
    // A cube input has no lat-long pixels: nothing recorded, whatever the setting.
    const fs::path cube = kShared / "orientation" / "OrientationCube.exr";
    if (fs::exists(cube)) {
        EXPECT_FALSE(ingestEnvironment({cube}, s).report.latLongPixels);
    }
    EXPECT_EQ(parseLatLongPixels("center"), LatLongPixels::Centre);
    EXPECT_THROW(parseLatLongPixels("middle"), SettingError);
    fs::remove_all(dir);
}

// The CLI flag: the placement in the KTX2 keys and the diffuse document; a bad value names the flag.
TEST(LatLongPixels, CommandsRecordThePlacement) {
    const fs::path dir = freshTempDir("latlong_cli");
    writeLatLong(dir / "sky.exr", 0.5f);
    const std::string in = (dir / "sky.exr").string();
    ASSERT_EQ(runCli("specular " + in + " -o " + (dir / "a.ktx2").string() +
                     " --size 8 --quality draft --backend cpu")
                  .exitCode,
              0);
    EXPECT_EQ(keyValue(dir / "a.ktx2", "iblbake.latlongPixels"), "centre");
    ASSERT_EQ(runCli("specular " + in + " -o " + (dir / "b.ktx2").string() +
                     " --size 8 --quality draft --backend cpu --latlong-pixels openexr")
                  .exitCode,
              0);
    EXPECT_EQ(keyValue(dir / "b.ktx2", "iblbake.latlongPixels"), "openexr");
    const CliRun diffuse =
        runCli("diffuse " + in + " -o " + (dir / "d.json").string() +
               " --size 16 --irradiance-size 8 --latlong-pixels openexr --irradiance-cube " +
               (dir / "irr.ktx2").string() + " --backend cpu");
    ASSERT_EQ(diffuse.exitCode, 0) << diffuse.err;
    EXPECT_EQ(readJson(dir / "d.json")["source"]["latlongPixels"], "openexr");
    EXPECT_EQ(keyValue(dir / "irr.ktx2", "iblbake.latlongPixels"), "openexr");

    const CliRun bad =
        runCli("specular " + in + " -o " + (dir / "c.ktx2").string() + " --latlong-pixels middle");
    EXPECT_NE(bad.exitCode, 0);
    EXPECT_EQ(lineCount(bad.err), 1) << bad.err;
    EXPECT_NE(bad.err.find("--latlong-pixels: 'middle' is not one of auto, centre, openexr"),
              std::string::npos)
        << bad.err;
    fs::remove_all(dir);
}

// `calibrate` keeps a lat-long's pixels: its output says which placement they are in, and a file that was
// read with OpenEXR's placement gets the envmap attribute again, so that ingest reads it back the same way.
TEST(LatLongPixels, CalibrateOutputKeepsThePlacement) {
    const fs::path file = kShared / "orientation" / "OrientationLatLong.exr";
    REQUIRE_FILE(file);
    const fs::path dir = freshTempDir("latlong_calibrate");
    for (const std::string placement : {"auto", "centre"}) {
        const fs::path out = dir / (placement + ".exr");
        const CliRun r = runCli("calibrate " + file.string() + " --scale 1 --size 16 --latlong-pixels " +
                                placement + " -o " + out.string());
        ASSERT_EQ(r.exitCode, 0) << r.err;
        const std::string expected = placement == "auto" ? "openexr" : "centre";
        auto in = OIIO::ImageInput::open(out.string());
        ASSERT_TRUE(in);
        EXPECT_EQ(in->spec().get_string_attribute("iblbake:latlongPixels"), expected);
        IngestSettings s;
        s.sourceFaceSize = 8;
        EXPECT_EQ(latLongPixelsName(*ingestEnvironment({out}, s).report.latLongPixels), expected);
    }
    fs::remove_all(dir);
}

// A scene bake records the placement in the specular and irradiance KTX2 keys, diffuse.json and the
// manifest; environment.latlongPixels overrides it and enters the stage keys (a changed placement re-bakes);
// a bad value names the key.
TEST(LatLongPixels, SceneBakeRecordsThePlacement) {
    const fs::path dir = freshTempDir("latlong_scene");
    writeLatLong(dir / "env.exr", 0.5f);
    json scene = {{"environment", {{"file", "env.exr"}}},
                  {"outputs",
                   {{"directory", "out"},
                    {"quality", "draft"},
                    {"faceSize", 16},
                    {"dfgSize", 16},
                    {"irradianceCube", true},
                    {"irradianceFaceSize", 8}}}};
    auto bake = [&](const std::string& placement) {
        if (placement.empty())
            scene["environment"].erase("latlongPixels");
        else
            scene["environment"]["latlongPixels"] = placement;
        writeText(dir / "scene.json", scene.dump(2));
        return runCli("bake " + (dir / "scene.json").string() + " --quiet --backend cpu");
    };
    for (const std::string placement : {"", "openexr"}) {
        const std::string expected = placement.empty() ? "centre" : placement;
        const CliRun r = bake(placement);
        ASSERT_EQ(r.exitCode, 0) << r.err;
        const fs::path out = dir / "out";
        EXPECT_EQ(keyValue(out / "specular.ktx2", "iblbake.latlongPixels"), expected);
        EXPECT_EQ(keyValue(out / "irradiance.ktx2", "iblbake.latlongPixels"), expected);
        EXPECT_EQ(readJson(out / "diffuse.json")["source"]["latlongPixels"], expected);
        EXPECT_EQ(readJson(out / "manifest.json")["latlongPixels"], expected);
    }
    const CliRun bad = bake("middle");
    EXPECT_NE(bad.exitCode, 0);
    EXPECT_EQ(lineCount(bad.err), 1) << bad.err;
    EXPECT_NE(bad.err.find("environment.latlongPixels"), std::string::npos) << bad.err;
    fs::remove_all(dir);
}
