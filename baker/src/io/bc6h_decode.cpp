// BC6H (unsigned) decoding, block by block as the Direct3D 11 functional specification's "BC6H format"
// decoding steps: mode, endpoint fields, partition, the transform of deltas, unquantize, the indices,
// interpolation and finish_unquantize.
#include "bc6h.h"
#include "bc6h_layout.h"
#include "small_float.h"

#include <algorithm>

namespace ibl::bc6h {

namespace {

int signExtend(int value, int bits) {
    const int sign = 1 << (bits - 1);
    return (value ^ sign) - sign;
}

} // namespace

BlockHalves decodeBlock(const std::uint8_t* block) {
    Bits128 bits;
    for (int i = 0; i < kBlockBytes; ++i)
        bits.word[i / 8] |= std::uint64_t(block[i]) << (8 * (i % 8));
    BlockHalves out{};
    const Mode* mode = modeOfBlock(block[0]);
    if (mode == nullptr) return out;

    std::array<int, 12> field{};
    int position = mode->modeBits;
    for (const BitRun& r : mode->runs) {
        if (isEnd(r)) break;
        const int step = r.first <= r.last ? 1 : -1;
        for (int b = r.first;; b += step) {
            field[r.field] |= bits.get(position++) << b;
            if (b == r.last) break;
        }
    }
    int partition = 0;
    if (mode->regions == 2)
        for (int i = 0; i < 5; ++i)
            partition |= bits.get(position++) << i;

    const int endpoints = 2 * mode->regions;
    const int mask = (1 << mode->endpointBits) - 1;
    std::array<std::array<int, 3>, 4> unquantized{};
    for (int e = 0; e < endpoints; ++e)
        for (int c = 0; c < 3; ++c) {
            int value = field[fieldOf(e, c)];
            if (mode->transformed && e > 0)
                value = (field[fieldOf(0, c)] + signExtend(value, mode->deltaBits[c])) & mask;
            unquantized[e][c] = unquantize(value, mode->endpointBits);
        }

    const int indexBits = mode->regions == 2 ? 3 : 4;
    for (int i = 0; i < kBlockTexels; ++i) {
        const bool anchor = i == 0 || (mode->regions == 2 && i == kAnchor2[std::size_t(partition)]);
        int index = 0;
        for (int b = 0; b < indexBits - (anchor ? 1 : 0); ++b)
            index |= bits.get(position++) << b;
        const int weight = indexBits == 3 ? kWeights3[std::size_t(index)] : kWeights4[std::size_t(index)];
        const int region = mode->regions == 2 ? regionOf(partition, i) : 0;
        for (int c = 0; c < 3; ++c)
            out[std::size_t(i)][std::size_t(c)] = std::uint16_t(finishUnquantize(
                interpolate(unquantized[2 * region][c], unquantized[2 * region + 1][c], weight)));
    }
    return out;
}

std::size_t blockCount(int width, int height) {
    return std::size_t((width + 3) / 4) * std::size_t((height + 3) / 4);
}

ImageRGBA decodeImage(const std::uint8_t* blocks, int width, int height) {
    ImageRGBA image(width, height);
    const int blocksX = (width + 3) / 4, blocksY = (height + 3) / 4;
    for (int by = 0; by < blocksY; ++by)
        for (int bx = 0; bx < blocksX; ++bx) {
            const BlockHalves texels = decodeBlock(
                blocks + kBlockBytes * (std::size_t(by) * std::size_t(blocksX) + std::size_t(bx)));
            for (int i = 0; i < kBlockTexels; ++i) {
                const int x = 4 * bx + i % 4, y = 4 * by + i / 4;
                if (x >= width || y >= height) continue;
                const auto& t = texels[std::size_t(i)];
                image.at(x, y) = {smallfloat::halfToFloat(t[0]), smallfloat::halfToFloat(t[1]),
                                  smallfloat::halfToFloat(t[2]), 1.0f};
            }
        }
    return image;
}

} // namespace ibl::bc6h
