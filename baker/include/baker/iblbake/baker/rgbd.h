// RGBD: HDR colour in an 8-bit RGBA PNG, as EXT_lights_image_based requires of its PNG images ("the
// alpha channel contains a value that, when the RGB channels are divided by it, can produce values
// greater than 1"). The exact packing is Babylon.js's toRGBD/fromRGBD (helperFunctions.fx), the
// implementation the extension was written for:
//   encode  D = clamp(floor(max(255 / max(r, g, b), 1)) / 255, 0, 1);  rgb' = (rgb x D)^(1/2.2)
//   decode  rgb = rgb'^2.2 / D
// Decoded values range over [0, 255]; D is an exact multiple of 1/255, so only rgb' is quantized.
#pragma once

#include "iblbake/core/image.h"

#include <array>
#include <cstdint>
#include <filesystem>

#include <glm/vec3.hpp>

namespace ibl {

inline constexpr float kRgbdMaxValue = 255.0f;

// 8-bit R, G, B, D of a linear colour (negative and non-finite channels become 0, values above
// kRgbdMaxValue clamp to it).
std::array<std::uint8_t, 4> encodeRgbd(const glm::vec3& linear);
glm::vec3 decodeRgbd(const std::array<std::uint8_t, 4>& rgbd);

// Writes `image` x `scale` as a straight-alpha (unassociated) RGBA PNG at `path`, with libpng's sRGB chunk
// (which browsers decode as an untagged PNG: no conversion; the Babylon.js glTF test reads these), through a
// temporary file and a rename, so a failure leaves nothing at `path`. Throws ibl::Error naming the file.
void writeRgbdPng(const std::filesystem::path& path, const ImageRGBA& image, float scale);

} // namespace ibl
