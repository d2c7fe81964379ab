// Damaged image files (truncated, bit-flipped; made here from good ones): the CLI answers each with
// success or a one-line error and a non-zero exit, never a crash, a hang or output without an error.
#include "cli_runner.h"

#include <gtest/gtest.h>

#include <OpenImageIO/imageio.h>

#include <fstream>
#include <random>
#include <vector>

namespace fs = std::filesystem;

namespace {

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

} // namespace
