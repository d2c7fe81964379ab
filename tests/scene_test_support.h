// Inputs and file helpers shared by the scene-bake and batch tests.
#pragma once

#include <gtest/gtest.h>

#include <OpenImageIO/imageio.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

namespace ibl::test {

// An RGB float image of w x h (pixels row by row), in the format the file name says.
inline void writeRgbFloatImage(const std::filesystem::path& file, int w, int h,
                               const std::vector<float>& pixels) {
    auto out = OIIO::ImageOutput::create(file.string());
    ASSERT_TRUE(out);
    ASSERT_TRUE(out->open(file.string(), OIIO::ImageSpec(w, h, 3, OIIO::TypeDesc::FLOAT)));
    ASSERT_TRUE(out->write_image(OIIO::TypeDesc::FLOAT, pixels.data()));
    out->close();
}

// A 64 x 32 lat-long: a sky gradient whose colour depends on `seed`.
inline void writeLatLong(const std::filesystem::path& file, float seed) {
    const int w = 64, h = 32;
    std::vector<float> pixels(std::size_t(w) * h * 3);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            float* p = &pixels[(std::size_t(y) * w + x) * 3];
            p[0] = 0.2f + seed * float(x) / w;
            p[1] = 0.5f + 0.5f * float(h - y) / h;
            p[2] = 1.0f - 0.5f * float(y) / h;
        }
    writeRgbFloatImage(file, w, h, pixels);
}

inline std::string readBytes(const std::filesystem::path& file) {
    std::ifstream in(file, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), {}};
}

inline void writeText(const std::filesystem::path& file, const std::string& text) {
    std::ofstream(file) << text;
}

} // namespace ibl::test
