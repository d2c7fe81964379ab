// RGBD packing (iblbake/baker/rgbd.h) and its PNG files.
#include "encoded_image.h"
#include "iblbake/baker/rgbd.h"
#include "iblbake/core/error.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace ibl {
namespace {

// Babylon.js's toGammaSpace/toLinearSpace approximation of sRGB.
constexpr float kGamma = 2.2f;

std::uint8_t quantize(float unit) {
    return std::uint8_t(std::lround(255.0f * std::clamp(unit, 0.0f, 1.0f)));
}

float finiteNonNegative(float v) {
    return std::isfinite(v) && v > 0.0f ? v : 0.0f;
}

} // namespace

std::array<std::uint8_t, 4> encodeRgbd(const glm::vec3& linear) {
    const glm::vec3 c(finiteNonNegative(linear.r), finiteNonNegative(linear.g), finiteNonNegative(linear.b));
    const float maxRgb = std::max({c.r, c.g, c.b, 1e-7f}); // Babylon's maxEps
    // D * 255 is an integer from 1 to 255, stored exactly in alpha.
    const float d255 = std::clamp(std::floor(std::max(kRgbdMaxValue / maxRgb, 1.0f)), 1.0f, 255.0f);
    const float d = d255 / 255.0f;
    return {quantize(std::pow(c.r * d, 1.0f / kGamma)), quantize(std::pow(c.g * d, 1.0f / kGamma)),
            quantize(std::pow(c.b * d, 1.0f / kGamma)), std::uint8_t(d255)};
}

glm::vec3 decodeRgbd(const std::array<std::uint8_t, 4>& rgbd) {
    const float d = float(std::max<std::uint8_t>(rgbd[3], 1)) / 255.0f;
    auto channel = [&](int c) { return std::pow(float(rgbd[c]) / 255.0f, kGamma) / d; };
    return {channel(0), channel(1), channel(2)};
}

void writeRgbdPng(const std::filesystem::path& path, const ImageRGBA& image, float scale) {
    std::vector<std::uint8_t> pixels(image.pixels.size() * 4);
    for (std::size_t i = 0; i < image.pixels.size(); ++i) {
        const auto rgbd = encodeRgbd(glm::vec3(image.pixels[i]) * scale);
        std::copy(rgbd.begin(), rgbd.end(), pixels.begin() + std::ptrdiff_t(4 * i));
    }
    // Alpha is D, not coverage: stored straight, as encodePng writes 8-bit RGBA.
    const std::vector<std::uint8_t> png = encodePng(path, image.width, image.height, 4, pixels.data());
    writeEncodedImage(path, std::string_view(reinterpret_cast<const char*>(png.data()), png.size()));
}

} // namespace ibl
