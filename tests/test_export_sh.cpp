// iblbake export-sh --profile filament against values derived by hand.
#include "cli_runner.h"

#include <iblbake/baker/latlong_pixels.h>

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <vector>

namespace fs = std::filesystem;
using ibl::test::CliRun;
using ibl::test::runCli;

namespace {

constexpr double kPi = 3.14159265358979323846;

// A lat-long of L(w) = 1 + w.y (docs/conventions.md mapping: row y at latitude pi (0.5 - v), v its centre in
// the pixel-centre placement that ingest reads a file without OpenEXR's envmap attribute with), as float EXR.
void writeLinearSky(const fs::path& path) {
    const int width = 256, height = 128;
    std::vector<float> pixels;
    for (int y = 0; y < height; ++y) {
        const double v = ibl::latLongPixelCentre(ibl::LatLongPixels::Centre, y, height);
        const float value = float(1.0 + std::sin(kPi * (0.5 - v)));
        for (int x = 0; x < width; ++x)
            pixels.insert(pixels.end(), {value, value, value});
    }
    auto out = OIIO::ImageOutput::create(path.string());
    ASSERT_TRUE(out);
    ASSERT_TRUE(out->open(path.string(), OIIO::ImageSpec(width, height, 3, OIIO::TypeDesc::FLOAT)));
    ASSERT_TRUE(out->write_image(OIIO::TypeDesc::FLOAT, pixels.data()));
    ASSERT_TRUE(out->close());
}

} // namespace

// For L = 1 + y: L_00 = sqrt(4 pi), L_1-1 = k_1 4 pi / 3, the rest 0. Filament's coefficient i is
// A_l k_i L_i / pi: c_0 = pi / (2 sqrt(pi)) 2 sqrt(pi) / pi = 1 and c_1 = (2 pi / 3) k_1^2 (4 pi / 3) / pi
// = (2/3)(3 / (4 pi))(4 pi / 3) = 2/3 -- E(n)/pi = 1 + (2/3) n.y, the cosine-weighted mean of 1 + y.
TEST(ExportSh, FilamentProfileMatchesHandDerivedCoefficients) {
    const fs::path dir = ibl::test::freshTempDir("export_sh");
    writeLinearSky(dir / "sky.exr");
    CliRun bake = runCli("diffuse " + (dir / "sky.exr").string() + " --size 64 --window none -o " +
                         (dir / "diffuse.json").string());
    ASSERT_EQ(bake.exitCode, 0) << bake.err;
    CliRun r = runCli("export-sh " + dir.string() + " --profile filament -o " + (dir / "sh.txt").string());
    ASSERT_EQ(r.exitCode, 0) << r.err;
    std::ifstream in(dir / "sh.txt");
    const double expected[9] = {1.0, 2.0 / 3.0, 0, 0, 0, 0, 0, 0, 0};
    std::string line;
    double worst = 0.0;
    for (int i = 0; i < 9; ++i) {
        ASSERT_TRUE(std::getline(in, line)) << "line " << i;
        float c[3];
        ASSERT_EQ(std::sscanf(line.c_str(), "(%f,%f,%f)", &c[0], &c[1], &c[2]), 3)
            << line; // Filament's parse
        for (float v : c) {
            EXPECT_NEAR(v, expected[i], 5e-4) << "coefficient " << i << ": " << line;
            worst = std::max(worst, std::abs(v - expected[i]));
        }
    }
    std::printf("largest deviation from the hand-derived coefficients: %.2e\n", worst);
    EXPECT_FALSE(std::getline(in, line)) << "more than 9 lines: " << line;
    fs::remove_all(dir);
}

TEST(ExportSh, RefusesAMissingBakeWithOneLine) {
    const fs::path dir = ibl::test::freshTempDir("export_sh_missing");
    CliRun r = runCli("export-sh " + dir.string() + " --profile filament -o " + (dir / "sh.txt").string());
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_EQ(ibl::test::lineCount(r.err), 1) << r.err;
    EXPECT_NE(r.err.find("diffuse.json"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(dir / "sh.txt"));
    fs::remove_all(dir);
}
