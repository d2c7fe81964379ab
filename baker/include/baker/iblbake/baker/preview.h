// Tone-mapped PNG previews of baked products, for people to look at (never read back by the tools).
#pragma once

#include "iblbake/core/cubemap.h"

#include <filesystem>
#include <vector>

namespace ibl {

// One row per level (every level, top = level 0), each the six faces side by side in +X, -X, +Y, -Y,
// +Z, -Z order, each face scaled to `tileSize` pixels (nearest texel). Exposure: the solid-angle-weighted
// median luminance of level 0 maps to 0.18 times 2^exposureEV; then Reinhard x / (1 + x) and the sRGB
// curve. Written atomically; throws ibl::Error naming the file.
void writeChainPreview(const std::filesystem::path& path, const CubeMapChain& chain, int tileSize = 96,
                       float exposureEV = 0.0f);

// A linear image as an 8-bit sRGB PNG: each channel times `scale`, Reinhard x / (1 + x), sRGB curve.
// Written atomically; throws ibl::Error naming the file.
void writeTonemappedPng(const std::filesystem::path& path, const ImageRGBA& image, float scale);

// The tone curve of writeTonemappedPng for one channel: linear x scale, Reinhard, sRGB curve, 8 bits.
unsigned char tonemapToSrgb8(float linear, float scale);

// 8-bit sRGB pixels (row-major, R, G, B per pixel) as a PNG. Written atomically; throws ibl::Error naming
// the file.
void writeSrgb8Png(const std::filesystem::path& path, int width, int height,
                   const std::vector<unsigned char>& rgb);

} // namespace ibl
