// Damaged image files (truncated, bit-flipped; made here from good ones): the CLI answers each with
// success or a one-line error and a non-zero exit, never a crash, a hang (ctest TIMEOUT, tests/
// CMakeLists.txt) or output without an error. KTX2 goes through every path that reads it.
#include "cli_runner.h"

#include <iblbake/core/error.h>
#include <iblbake/ktx2/ktx2.h>
#include <iblbake/runtime/runtime.h>

#include <gtest/gtest.h>

#include <OpenImageIO/imageio.h>

#include <fstream>
#include <random>
#include <vector>

namespace fs = std::filesystem;

namespace {

using namespace ibl;
using namespace ibl::test;

std::vector<char> readBytes(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), {}};
}

void writeBytes(const fs::path& path, const std::vector<char>& bytes) {
    std::ofstream(path, std::ios::binary).write(bytes.data(), std::streamsize(bytes.size()));
}

// A small good file of each format, written with OpenImageIO from a gradient.
fs::path writeGood(const fs::path& dir, const std::string& name) {
    const int w = 64, h = 32;
    std::vector<float> pixels(std::size_t(w) * h * 3);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int c = 0; c < 3; ++c)
                pixels[(std::size_t(y) * w + x) * 3 + c] = 0.1f + float(x + c * y) / 64.0f;
    fs::path path = dir / name;
    auto out = OIIO::ImageOutput::create(path.string());
    OIIO::ImageSpec spec(w, h, 3, name.ends_with(".png") ? OIIO::TypeDesc::UINT8 : OIIO::TypeDesc::FLOAT);
    out->open(path.string(), spec);
    out->write_image(OIIO::TypeDesc::FLOAT, pixels.data());
    out->close();
    return path;
}

TEST(DamagedInputs, TruncatedAndBitFlippedImagesNeverCrash) {
    fs::path dir = freshTempDir("damaged");
    std::mt19937 random(1234);
    int cases = 0;
    for (const std::string name : {"good.hdr", "good.exr", "good.png"}) {
        std::vector<char> good = readBytes(writeGood(dir, name));
        ASSERT_GT(good.size(), 64u) << name;
        std::vector<std::vector<char>> damaged;
        for (double keep : {0.0, 0.02, 0.1, 0.5, 0.9})
            damaged.emplace_back(good.begin(), good.begin() + std::ptrdiff_t(keep * good.size()));
        for (int flips = 0; flips < 6; ++flips) {
            std::vector<char> bytes = good;
            std::size_t limit =
                flips < 3 ? std::min<std::size_t>(bytes.size(), 128) : bytes.size(); // header, anywhere
            for (int k = 0; k < 4; ++k)
                bytes[random() % limit] ^= char(1 << (random() % 8));
            damaged.push_back(bytes);
        }
        for (std::size_t i = 0; i < damaged.size(); ++i, ++cases) {
            fs::path input = dir / ("damaged_" + std::to_string(i) + "_" + name);
            writeBytes(input, damaged[i]);
            fs::path output = dir / "out.ktx2";
            CliRun r =
                runCli("specular " + input.string() +
                       " --size 8 --quality draft --backend cpu --layout latlong -o " + output.string());
            // 0: the damage did not matter; 1: a clean, one-line refusal. A crash would be 128+ / -1.
            ASSERT_TRUE(r.exitCode == 0 || r.exitCode == 1)
                << input << " exit " << r.exitCode << ": " << r.err;
            if (r.exitCode == 0) {
                EXPECT_TRUE(fs::exists(output)) << input;
            } else {
                EXPECT_EQ(lineCount(r.err), 1) << input << ": " << r.err;
                EXPECT_NE(r.err.find(input.filename().string()), std::string::npos) << r.err;
                EXPECT_FALSE(fs::exists(output)) << input;
            }
            fs::remove(output);
        }
    }
    EXPECT_EQ(cases, 33);
    fs::remove_all(dir);
}

// A clean refusal of `input` by the CLI: exit 1, one line on stderr naming the file, `output` not written.
void expectCleanRefusalOrSuccess(const CliRun& r, const std::string& input, const fs::path& output) {
    ASSERT_TRUE(r.exitCode == 0 || r.exitCode == 1) << input << " exit " << r.exitCode << ": " << r.err;
    if (r.exitCode == 0) {
        EXPECT_TRUE(fs::exists(output)) << input;
    } else {
        EXPECT_EQ(lineCount(r.err), 1) << input << ": " << r.err;
        EXPECT_NE(r.err.find(input), std::string::npos) << r.err;
        EXPECT_FALSE(fs::exists(output)) << input;
    }
}

// Damaged copies of a good KTX2: truncations at every structure boundary, random bit flips in the
// metadata and anywhere.
std::vector<std::vector<char>> damagedCopies(const std::vector<char>& good) {
    std::vector<std::vector<char>> damaged;
    for (std::size_t keep : {std::size_t(0), std::size_t(1), std::size_t(12), std::size_t(79),
                             std::size_t(80), std::size_t(104), good.size() / 2, good.size() - 1})
        damaged.emplace_back(good.begin(), good.begin() + std::ptrdiff_t(keep));
    std::mt19937 random(4321);
    for (int flips = 0; flips < 12; ++flips) {
        std::vector<char> bytes = good;
        const std::size_t limit = flips < 8 ? 400 : bytes.size(); // header, index, DFD and key/values
        for (int k = 0; k < 4; ++k)
            bytes[random() % limit] ^= char(1 << (random() % 8));
        damaged.push_back(bytes);
    }
    return damaged;
}

TEST(DamagedInputs, DamagedKtx2IsRefusedByEveryReader) {
    const fs::path dir = freshTempDir("damaged_ktx2");
    const fs::path bake = dir / "bake";
    fs::create_directories(bake);
    const std::string sample = std::string(IBLBAKE_SOURCE_DIR) + "/data/rooitou_park_1k.hdr";
    const fs::path good = dir / "good.ktx2";
    ASSERT_EQ(
        runCli("dfg --size 16 --samples 64 --backend cpu -o " + (bake / "dfg_lut.exr").string()).exitCode, 0);
    ASSERT_EQ(runCli("diffuse " + sample + " --size 16 --quality draft --backend cpu -o " +
                     (bake / "diffuse.json").string())
                  .exitCode,
              0);
    ASSERT_EQ(runCli("specular " + sample + " --size 16 --quality draft --backend cpu --scale 2 -o " +
                     good.string())
                  .exitCode,
              0);
    const fs::path preview = dir / "preview.png";
    const std::string previewArgs = " -o " + preview.string() + " --sphere-size 8 --backend cpu";
    fs::copy_file(good, bake / "specular.ktx2");
    ASSERT_EQ(runCli("preview " + bake.string() + previewArgs).exitCode, 0) << "the good bake must render";
    fs::remove(preview);
    fs::remove(dir / "preview.exr");

    const std::vector<std::vector<char>> damaged = damagedCopies(readBytes(good));
    int refused = 0;
    for (std::size_t i = 0; i < damaged.size(); ++i) {
        const fs::path input = dir / ("damaged_" + std::to_string(i) + ".ktx2");
        writeBytes(input, damaged[i]);
        // The runtime's loader: a probe chain or ibl::Error naming the file on one line, nothing else.
        try {
            loadLdKtx2(input);
        } catch (const ibl::Error& e) {
            ++refused;
            const std::string message = e.what();
            EXPECT_EQ(message.find('\n'), std::string::npos) << message;
            EXPECT_NE(message.find(input.string()), std::string::npos) << message;
        }
        // `iblbake preview` on a bake directory holding it.
        fs::copy_file(input, bake / "specular.ktx2", fs::copy_options::overwrite_existing);
        expectCleanRefusalOrSuccess(runCli("preview " + bake.string() + previewArgs), "specular.ktx2",
                                    preview);
        fs::remove(preview);
        fs::remove(dir / "preview.exr");
        // `iblbake inspect` reads images through OpenImageIO, which has no KTX2 reader: always a refusal.
        CliRun inspected = runCli("inspect " + input.string());
        EXPECT_EQ(inspected.exitCode, 1) << inspected.err;
        EXPECT_EQ(lineCount(inspected.err), 1) << inspected.err;
        EXPECT_NE(inspected.err.find(input.string()), std::string::npos) << inspected.err;
    }
    // Every truncation and most flips in the metadata must be caught (flips in texel data may not be).
    EXPECT_GE(refused, 8 + 4);

    // Structurally valid files whose iblbake metadata is damaged: the loader and `preview --reference`
    // (which reads the calibration factor) refuse them by name.
    const Ktx2Image goodImage = readKtx2(good);
    CubeMapChain chain;
    for (const std::vector<ImageRGBA>& level : goodImage.levels) {
        CubeMap cube(level[0].width);
        for (int f = 0; f < 6; ++f)
            cube.faces[f] = level[std::size_t(f)];
        chain.levels.push_back(cube);
    }
    const std::pair<std::string, std::string> badValues[] = {
        {"iblbake.roughnessMapping", "bogus\nsecond line"},
        {"iblbake.calibration.factor", "nan"},
        {"iblbake.calibration.factor", "-2"},
        {"iblbake.calibration.factor", "1e999"},
        {"iblbake.calibration.factor", "2 lux"}};
    for (const auto& [key, value] : badValues) {
        writeKtx2Cube(bake / "specular.ktx2", chain, Ktx2Format::RGBA16F, {{key, value}});
        CliRun r = runCli("preview " + bake.string() + " --reference " + sample + previewArgs);
        EXPECT_EQ(r.exitCode, 1) << key << " = " << value << ": " << r.err;
        expectCleanRefusalOrSuccess(r, "specular.ktx2", preview);
    }
    fs::remove_all(dir);
}

} // namespace
