#include "iblbake/baker/preview.h"
#include "encoded_image.h"
#include "iblbake/core/error.h"
#include "iblbake/core/numeric.h"

#include <cube.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace ibl {
namespace {

float medianLuminance(const CubeMap& cube) {
    struct Sample {
        float lum, omega;
    };
    std::vector<Sample> samples;
    double total = 0.0;
    for (int f = 0; f < 6; ++f)
        for (int y = 0; y < cube.faceSize; ++y)
            for (int x = 0; x < cube.faceSize; ++x) {
                float omega = cubeTexelSolidAngle(x, y, cube.faceSize);
                samples.push_back({rec709Luminance(cube.faces[f].at(x, y)), omega});
                total += omega;
            }
    std::sort(samples.begin(), samples.end(), [](const Sample& a, const Sample& b) { return a.lum < b.lum; });
    double accumulated = 0.0;
    for (const Sample& s : samples)
        if ((accumulated += s.omega) >= 0.5 * total) return s.lum;
    return samples.empty() ? 0.0f : samples.back().lum;
}

// IEC 61966-2-1 (Frostbite Listing 30).
float encodeSrgb(float linear) {
    linear = std::clamp(linear, 0.0f, 1.0f);
    return linear <= 0.0031308f ? 12.92f * linear : 1.055f * std::pow(linear, 1.0f / 2.4f) - 0.055f;
}

} // namespace

void writeSrgb8Png(const std::filesystem::path& path, int width, int height,
                   const std::vector<unsigned char>& rgb) {
    const std::vector<std::uint8_t> png = encodePng(path, width, height, 3, rgb.data());
    writeEncodedImage(path, std::string_view(reinterpret_cast<const char*>(png.data()), png.size()));
}

unsigned char tonemapToSrgb8(float linear, float scale) {
    float v = std::max(linear * scale, 0.0f);
    return (unsigned char)std::lround(255.0f * encodeSrgb(v / (1.0f + v)));
}

void writeTonemappedPng(const std::filesystem::path& path, const ImageRGBA& image, float scale) {
    std::vector<unsigned char> rgb(image.pixels.size() * 3);
    for (std::size_t i = 0; i < image.pixels.size(); ++i)
        for (int c = 0; c < 3; ++c)
            rgb[i * 3 + c] = tonemapToSrgb8(image.pixels[i][c], scale);
    writeSrgb8Png(path, image.width, image.height, rgb);
}

void writeChainPreview(const std::filesystem::path& path, const CubeMapChain& chain, int tileSize,
                       float exposureEV) {
    if (chain.levels.empty()) throw Error(path.string() + ": nothing to preview");
    const int gap = 4, width = 6 * tileSize + 5 * gap;
    const int rows = int(chain.levels.size()), height = rows * tileSize + (rows - 1) * gap;
    const float median = medianLuminance(chain.levels[0]);
    const float scale = (median > 0.0f ? 0.18f / median : 1.0f) * std::exp2(exposureEV);
    std::vector<unsigned char> pixels(std::size_t(width) * height * 3, 24); // dark grey gaps
    for (int m = 0; m < rows; ++m) {
        const CubeMap& level = chain.levels[std::size_t(m)];
        for (int f = 0; f < 6; ++f)
            for (int y = 0; y < tileSize; ++y)
                for (int x = 0; x < tileSize; ++x) {
                    const glm::vec4& texel =
                        level.faces[f].at(x * level.faceSize / tileSize, y * level.faceSize / tileSize);
                    std::size_t o =
                        (std::size_t(m * (tileSize + gap) + y) * width + f * (tileSize + gap) + x) * 3;
                    for (int c = 0; c < 3; ++c)
                        pixels[o + c] = tonemapToSrgb8(texel[c], scale);
                }
    }
    writeSrgb8Png(path, width, height, pixels);
}

} // namespace ibl
