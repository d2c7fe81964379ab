// Radiance RGBE pixels kept as stored: three 8-bit mantissas and their shared exponent (Ward, "Real
// Pixels", Graphics Gems II), 4 bytes a pixel where float RGBA takes 16. A lat-long read from a Radiance
// file stays in this form up to the resampling (ingest.cpp) when nothing before it changes a value: memory
// touched for the first time costs a page fault per 4 KB (read_image.cpp), and a 1k map's floats were
// 2,048 of the ~4,400 faults of `iblbake diffuse`.
#pragma once

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/vec4.hpp>

namespace ibl::ingest {

// The float a mantissa holds at exponent e: mantissa * kRgbeExponentScale[e] (0 for e = 0: black). Exact
// in float, as ldexp(mantissa, e - (128 + 8)) is: a mantissa of at most 8 bits times a power of two (the
// smallest scales are subnormal floats, and so are their products, still exact). No half-step is added (as
// rgbe.c and OpenImageIO decode; Radiance's own colr_color adds 0.5), so values are those of the readers
// the files were checked in.
inline const std::array<float, 256> kRgbeExponentScale = [] {
    std::array<float, 256> scale{};
    for (int e = 1; e < 256; ++e)
        scale[std::size_t(e)] = std::ldexp(1.0f, e - (128 + 8));
    return scale;
}();

using RgbePixel = std::array<std::uint8_t, 4>; // R, G, B mantissas, exponent
static_assert(sizeof(RgbePixel) == 4, "RGBE rows are read into RgbePixel arrays as bytes");

inline glm::vec4 decodeRgbe(const RgbePixel& p) {
    const float scale = kRgbeExponentScale[p[3]];
    return {float(p[0]) * scale, float(p[1]) * scale, float(p[2]) * scale, 1.0f};
}

struct ImageRGBE {
    int width = 0;
    int height = 0;
    std::vector<RgbePixel> pixels; // row-major, first row = first scanline

    glm::vec4 at(int x, int y) const {
        return decodeRgbe(pixels[std::size_t(y) * std::size_t(width) + std::size_t(x)]);
    }
};

} // namespace ibl::ingest
