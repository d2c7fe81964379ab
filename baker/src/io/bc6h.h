// BC6H (unsigned half, VK_FORMAT_BC6H_UFLOAT_BLOCK, DXGI_FORMAT_BC6H_UF16): our encoder and decoder, written
// from the Khronos Data Format Specification's "BC6H" section and the Direct3D 11 functional specification
// (bc6h_layout.h). A block holds 4 x 4 texels in 16 bytes; an image of w x h texels is ceil(w / 4) x
// ceil(h / 4) blocks in rows, and a level smaller than 4 texels (2 x 2, 1 x 1) is one block whose texels
// outside the image repeat the nearest edge texel (docs/formats.md "BC6H").
#pragma once

#include "iblbake/core/image.h"

#include <array>
#include <cstddef>
#include <cstdint>

namespace ibl::bc6h {

// The encoder's effort (docs/formats.md "BC6H"): Fast tries mode 11 (one region, 10-bit endpoints); Default
// every one-region mode, and where the best of them is not within about 0.5%, the two most compact of the 32
// two-region partitions in every two-region mode, the best candidate refitted once (least squares); Best
// always the eight most compact partitions, every candidate refitted up to three times.
enum class Preset { Fast, Default, Best };

using Block = std::array<std::uint8_t, 16>;
// 16 texels (row by row) of three halves' bit patterns, each 0..0x7BFF (no sign, no Inf or NaN).
using BlockHalves = std::array<std::array<std::uint16_t, 3>, 16>;

BlockHalves decodeBlock(const std::uint8_t* block);
Block encodeBlock(const BlockHalves& texels, Preset preset);

std::size_t blockCount(int width, int height);

// Encodes the RGB of `image` (alpha is not stored) into blockCount(width, height) blocks at `out`, blocks in
// parallel (TBB). Every channel must be finite and in [0, 65504] (the caller refuses anything else).
void encodeImage(const ImageRGBA& image, Preset preset, std::uint8_t* out);

// The image of `width` x `height` texels that the blocks at `blocks` hold, alpha 1.
ImageRGBA decodeImage(const std::uint8_t* blocks, int width, int height);

} // namespace ibl::bc6h
