// `iblbake preview` on a small bake of the sample HDRI: the labelled grid and the linear EXR written,
// per-column error against the brute-force reference printed and bounded; a bad bake directory refused.
#include "cli_runner.h"

#include <iblbake/baker/material_preview.h>

#include <gtest/gtest.h>

#include <OpenImageIO/imageio.h>

#include <regex>

namespace fs = std::filesystem;

namespace {

using namespace ibl::test;

// An 8-bit RGB PNG's pixels.
struct Png {
    int width = 0, height = 0;
    std::vector<unsigned char> rgb;
    bool differsFrom(int x, int y, int w, int h, unsigned char background) const {
        for (int j = y; j < y + h; ++j)
            for (int i = x; i < x + w; ++i)
                for (int c = 0; c < 3; ++c)
                    if (rgb[(std::size_t(j) * width + i) * 3 + c] != background) return true;
        return false;
    }
};

Png readPng(const fs::path& file) {
    auto in = OIIO::ImageInput::open(file.string());
    EXPECT_TRUE(in) << file;
    if (!in) return {};
    Png png{in->spec().width, in->spec().height, {}};
    png.rgb.resize(std::size_t(png.width) * png.height * 3);
    EXPECT_TRUE(in->read_image(0, 0, 0, 3, OIIO::TypeDesc::UINT8, png.rgb.data()));
    return png;
}

// The grid's layout follows from the column count and the ball size, and every label region holds text:
// the roughness above each column, the name of each row, the values of the error scale.
void expectLabelledGrid(const fs::path& file, int sphereSize, bool withReference) {
    const ibl::PreviewLayout layout = ibl::previewLayout(sphereSize, withReference);
    EXPECT_EQ(layout.columnWidth, std::max(sphereSize, 4 * layout.fontSize));
    EXPECT_EQ(layout.width,
              2 * layout.margin + layout.labelWidth + ibl::kPreviewColumns * layout.columnWidth);
    EXPECT_EQ(layout.rowCount, withReference ? 6 : 2);
    const Png png = readPng(file);
    ASSERT_EQ(png.width, layout.width);
    ASSERT_EQ(png.height, layout.height);
    const unsigned char background = png.rgb[0]; // the top-left corner is margin
    for (int c = 0; c < ibl::kPreviewColumns; ++c)
        EXPECT_TRUE(png.differsFrom(layout.cellX(c), layout.headerHeight - 2 * layout.fontSize, sphereSize,
                                    2 * layout.fontSize, background))
            << "roughness label of column " << c;
    for (int r = 0; r < layout.rowCount; ++r) {
        EXPECT_TRUE(
            png.differsFrom(layout.margin, layout.cellY(r), layout.labelWidth, sphereSize, background))
            << "name of row " << r;
        for (int c = 0; c < ibl::kPreviewColumns; ++c)
            EXPECT_TRUE(png.differsFrom(layout.cellX(c), layout.cellY(r), sphereSize, sphereSize, background))
                << "ball of row " << r << ", column " << c;
    }
    if (withReference) { // the colour scale and its values, below the last row's error values
        EXPECT_TRUE(png.differsFrom(layout.cellX(0), layout.height - layout.margin - layout.legendHeight,
                                    ibl::kPreviewColumns * layout.columnWidth / 2, layout.legendHeight,
                                    background));
    }
    EXPECT_EQ(layout.legendHeight > 0, withReference);
}

TEST(CliPreview, RendersTheBakeBesideTheReference) {
    fs::path dir = freshTempDir("preview");
    const std::string d = dir.string();
    const std::string calibration = " --sun-illuminance 100000 --extract-sun --sun-json " + d + "/sun.json";
    ASSERT_EQ(runCli("dfg --size 32 --samples 256 -o " + d + "/dfg_lut.exr").exitCode, 0);
    ASSERT_EQ(runCli("specular " + kSampleHdri + " --size 64" + calibration + " -o " + d +
                     "/specular.ktx2 --rough-layers " + d + "/specular_rough.ktx2")
                  .exitCode,
              0);
    ASSERT_EQ(
        runCli("diffuse " + kSampleHdri + " --size 64" + calibration + " -o " + d + "/diffuse.json").exitCode,
        0);
    CliRun r =
        runCli("preview " + d + " --reference " + kSampleHdri + " --sphere-size 16 -o " + d + "/preview.png");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.out.find("and its rough layers"), std::string::npos) << r.out; // the loose file, by its name
    expectLabelledGrid(dir / "preview.png", 16, true);
    auto exr = OIIO::ImageInput::open(d + "/preview.exr");
    ASSERT_TRUE(exr);
    EXPECT_EQ(exr->spec().width, 3 * 11 * 16); // runtime | reference | heat map, linear
    EXPECT_EQ(exr->spec().height, 2 * 16);
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

    // Without a reference: the two runtime rows, no error scale.
    r = runCli("preview " + d + " --sphere-size 24 --backend cpu -o " + d + "/runtime.png");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    expectLabelledGrid(dir / "runtime.png", 24, false);
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
