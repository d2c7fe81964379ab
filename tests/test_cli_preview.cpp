// `iblbake preview` on a small bake of the sample HDRI: picture and linear EXR written, per-column
// error against the brute-force reference printed and bounded; a bad bake directory refused.
#include "cli_runner.h"

#include <gtest/gtest.h>

#include <OpenImageIO/imageio.h>

#include <regex>

namespace fs = std::filesystem;

namespace {

using namespace ibl::test;

TEST(CliPreview, RendersTheBakeBesideTheReference) {
    fs::path dir = freshTempDir("preview");
    const std::string d = dir.string();
    const std::string calibration = " --sun-illuminance 100000 --extract-sun --sun-json " + d + "/sun.json";
    ASSERT_EQ(runCli("dfg --size 32 --samples 256 -o " + d + "/dfg_lut.exr").exitCode, 0);
    ASSERT_EQ(runCli("specular " + kSampleHdri + " --size 64" + calibration + " -o " + d + "/specular.ktx2")
                  .exitCode,
              0);
    ASSERT_EQ(
        runCli("diffuse " + kSampleHdri + " --size 64" + calibration + " -o " + d + "/diffuse.json").exitCode,
        0);
    CliRun r =
        runCli("preview " + d + " --reference " + kSampleHdri + " --sphere-size 16 -o " + d + "/preview.png");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    auto png = OIIO::ImageInput::open(d + "/preview.png");
    ASSERT_TRUE(png);
    EXPECT_EQ(png->spec().width, 3 * 11 * 16); // runtime | reference | heat map
    EXPECT_EQ(png->spec().height, 2 * 16);
    EXPECT_TRUE(fs::exists(dir / "preview.exr"));
    // Every roughness column within 10% of the reference (sun extracted: residual probe + disk light
    // against the full map).
    std::smatch columns;
    ASSERT_TRUE(std::regex_search(r.out, columns, std::regex("both rows\\):(.*)"))) << r.out;
    std::string list = columns[1];
    std::regex percent("([0-9.]+)%");
    int count = 0;
    for (auto it = std::sregex_iterator(list.begin(), list.end(), percent); it != std::sregex_iterator();
         ++it, ++count)
        EXPECT_LT(std::stod((*it)[1]), 10.0) << r.out;
    EXPECT_EQ(count, 11);
    fs::remove_all(dir);
}

TEST(CliPreview, MissingBakeIsOneLineAndNonZero) {
    fs::path dir = freshTempDir("preview_bad");
    CliRun r = runCli("preview " + dir.string() + " -o " + (dir / "preview.png").string());
    EXPECT_NE(r.exitCode, 0);
    EXPECT_EQ(lineCount(r.err), 1) << r.err;
    EXPECT_NE(r.err.find("specular.ktx2"), std::string::npos) << r.err;
    EXPECT_EQ(entryCount(dir), 0u);
    fs::remove_all(dir);
}

} // namespace
