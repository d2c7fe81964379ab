// The BC6H block format (unsigned half), shared by the encoder and the decoder: the 14 modes' bit layouts,
// endpoint and delta precisions, the 32 two-region partitions with their anchors, the interpolation weights,
// and the spec's "unquantize" and "finish_unquantize" for the unsigned format. Source: the Khronos Data
// Format Specification, section "BC6H", and the Direct3D 11 functional specification, "BC6H format" (mode
// table, "Bit layouts", "Partition sets").
#pragma once

#include <array>
#include <cstdint>

namespace ibl::bc6h {

inline constexpr int kBlockBytes = 16;
inline constexpr int kBlockTexels = 16; // 4 x 4, texel i at column i % 4, row i / 4
inline constexpr int kHalfMaxBits = 0x7BFF;

// The endpoint fields of a block: endpoint e (0..3; region 0 holds e 0 and 1, region 1 holds e 2 and 3),
// channel c (R, G, B) is field 3 e + c. The specification names them w (e 0), x (1), y (2), z (3).
inline constexpr int fieldOf(int endpoint, int channel) {
    return 3 * endpoint + channel;
}

// A run of one field's bits as they follow each other in the block: bits first, first +- 1, ..., last of the
// field (most runs go up from bit 0; modes 13 and 14 store the top bits of w in reverse).
struct BitRun {
    std::uint8_t field;
    std::uint8_t first;
    std::uint8_t last;
};

struct Mode {
    std::uint8_t number;   // the specification's mode number, 1..14
    std::uint8_t modeBits; // 2 (modes 1, 2) or 5
    std::uint8_t code;     // the mode bits' value
    std::uint8_t regions;  // 2 (modes 1..10) or 1
    bool transformed;      // endpoints 1..3 stored as signed deltas from endpoint 0
    std::uint8_t endpointBits;
    std::array<std::uint8_t, 3> deltaBits; // per channel; equal to endpointBits when not transformed
    std::array<BitRun, 24> runs; // after the mode bits, before the partition bits; ended by an empty run
};

// A run of no bits ends a mode's list: bit 0 of w's red alone, which no layout has (it begins a longer run).
inline constexpr bool isEnd(const BitRun& r) {
    return r.field == 0 && r.first == 0 && r.last == 0;
}

// Shorthands for the layouts below: W(c, lo, hi) the bits lo..hi of endpoint 0's channel c, X, Y and Z those
// of endpoints 1, 2 and 3; a single bit is B(endpoint, c, bit).
inline constexpr BitRun run(int endpoint, int channel, int first, int last) {
    return {std::uint8_t(fieldOf(endpoint, channel)), std::uint8_t(first), std::uint8_t(last)};
}
inline constexpr BitRun bit(int endpoint, int channel, int b) {
    return run(endpoint, channel, b, b);
}
inline constexpr int R = 0, G = 1, B = 2;

// D3D11 "BC6H format", the bit layout of each mode, in block order after the mode bits.
inline constexpr std::array<Mode, 14> kModes = {{
    {1,
     2,
     0x00,
     2,
     true,
     10,
     {5, 5, 5},
     {{bit(2, G, 4), bit(2, B, 4), bit(3, B, 4), run(0, R, 0, 9), run(0, G, 0, 9), run(0, B, 0, 9),
       run(1, R, 0, 4), bit(3, G, 4), run(2, G, 0, 3), run(1, G, 0, 4), bit(3, B, 0), run(3, G, 0, 3),
       run(1, B, 0, 4), bit(3, B, 1), run(2, B, 0, 3), run(2, R, 0, 4), bit(3, B, 2), run(3, R, 0, 4),
       bit(3, B, 3)}}},
    {2, 2, 0x01, 2, true, 7, {6, 6, 6}, {{bit(2, G, 5),    bit(3, G, 4),    bit(3, G, 5),    run(0, R, 0, 6),
                                          bit(3, B, 0),    bit(3, B, 1),    bit(2, B, 4),    run(0, G, 0, 6),
                                          bit(2, B, 5),    bit(3, B, 2),    bit(2, G, 4),    run(0, B, 0, 6),
                                          bit(3, B, 3),    bit(3, B, 5),    bit(3, B, 4),    run(1, R, 0, 5),
                                          run(2, G, 0, 3), run(1, G, 0, 5), run(3, G, 0, 3), run(1, B, 0, 5),
                                          run(2, B, 0, 3), run(2, R, 0, 5), run(3, R, 0, 5)}}},
    {3,
     5,
     0x02,
     2,
     true,
     11,
     {5, 4, 4},
     {{run(0, R, 0, 9), run(0, G, 0, 9), run(0, B, 0, 9), run(1, R, 0, 4), bit(0, R, 10), run(2, G, 0, 3),
       run(1, G, 0, 3), bit(0, G, 10), bit(3, B, 0), run(3, G, 0, 3), run(1, B, 0, 3), bit(0, B, 10),
       bit(3, B, 1), run(2, B, 0, 3), run(2, R, 0, 4), bit(3, B, 2), run(3, R, 0, 4), bit(3, B, 3)}}},
    {4, 5, 0x06, 2, true, 11, {4, 5, 4}, {{run(0, R, 0, 9), run(0, G, 0, 9), run(0, B, 0, 9), run(1, R, 0, 3),
                                           bit(0, R, 10),   bit(3, G, 4),    run(2, G, 0, 3), run(1, G, 0, 4),
                                           bit(0, G, 10),   run(3, G, 0, 3), run(1, B, 0, 3), bit(0, B, 10),
                                           bit(3, B, 1),    run(2, B, 0, 3), run(2, R, 0, 3), bit(3, B, 0),
                                           bit(3, B, 2),    run(3, R, 0, 3), bit(2, G, 4),    bit(3, B, 3)}}},
    {5, 5, 0x0A, 2, true, 11, {4, 4, 5}, {{run(0, R, 0, 9), run(0, G, 0, 9), run(0, B, 0, 9), run(1, R, 0, 3),
                                           bit(0, R, 10),   bit(2, B, 4),    run(2, G, 0, 3), run(1, G, 0, 3),
                                           bit(0, G, 10),   bit(3, B, 0),    run(3, G, 0, 3), run(1, B, 0, 4),
                                           bit(0, B, 10),   run(2, B, 0, 3), run(2, R, 0, 3), bit(3, B, 1),
                                           bit(3, B, 2),    run(3, R, 0, 3), bit(3, B, 4),    bit(3, B, 3)}}},
    {6,
     5,
     0x0E,
     2,
     true,
     9,
     {5, 5, 5},
     {{run(0, R, 0, 8), bit(2, B, 4), run(0, G, 0, 8), bit(2, G, 4), run(0, B, 0, 8), bit(3, B, 4),
       run(1, R, 0, 4), bit(3, G, 4), run(2, G, 0, 3), run(1, G, 0, 4), bit(3, B, 0), run(3, G, 0, 3),
       run(1, B, 0, 4), bit(3, B, 1), run(2, B, 0, 3), run(2, R, 0, 4), bit(3, B, 2), run(3, R, 0, 4),
       bit(3, B, 3)}}},
    {7,
     5,
     0x12,
     2,
     true,
     8,
     {6, 5, 5},
     {{run(0, R, 0, 7), bit(3, G, 4), bit(2, B, 4), run(0, G, 0, 7), bit(3, B, 2), bit(2, G, 4),
       run(0, B, 0, 7), bit(3, B, 3), bit(3, B, 4), run(1, R, 0, 5), run(2, G, 0, 3), run(1, G, 0, 4),
       bit(3, B, 0), run(3, G, 0, 3), run(1, B, 0, 4), bit(3, B, 1), run(2, B, 0, 3), run(2, R, 0, 5),
       run(3, R, 0, 5)}}},
    {8, 5, 0x16, 2, true, 8, {5, 6, 5}, {{run(0, R, 0, 7), bit(3, B, 0),    bit(2, B, 4),    run(0, G, 0, 7),
                                          bit(2, G, 5),    bit(2, G, 4),    run(0, B, 0, 7), bit(3, G, 5),
                                          bit(3, B, 4),    run(1, R, 0, 4), bit(3, G, 4),    run(2, G, 0, 3),
                                          run(1, G, 0, 5), run(3, G, 0, 3), run(1, B, 0, 4), bit(3, B, 1),
                                          run(2, B, 0, 3), run(2, R, 0, 4), bit(3, B, 2),    run(3, R, 0, 4),
                                          bit(3, B, 3)}}},
    {9, 5, 0x1A, 2, true, 8, {5, 5, 6}, {{run(0, R, 0, 7), bit(3, B, 1),    bit(2, B, 4),    run(0, G, 0, 7),
                                          bit(2, B, 5),    bit(2, G, 4),    run(0, B, 0, 7), bit(3, B, 5),
                                          bit(3, B, 4),    run(1, R, 0, 4), bit(3, G, 4),    run(2, G, 0, 3),
                                          run(1, G, 0, 4), bit(3, B, 0),    run(3, G, 0, 3), run(1, B, 0, 5),
                                          run(2, B, 0, 3), run(2, R, 0, 4), bit(3, B, 2),    run(3, R, 0, 4),
                                          bit(3, B, 3)}}},
    {10, 5, 0x1E, 2, false, 6, {6, 6, 6}, {{run(0, R, 0, 5), bit(3, G, 4),    bit(3, B, 0),
                                            bit(3, B, 1),    bit(2, B, 4),    run(0, G, 0, 5),
                                            bit(2, G, 5),    bit(2, B, 5),    bit(3, B, 2),
                                            bit(2, G, 4),    run(0, B, 0, 5), bit(3, G, 5),
                                            bit(3, B, 3),    bit(3, B, 5),    bit(3, B, 4),
                                            run(1, R, 0, 5), run(2, G, 0, 3), run(1, G, 0, 5),
                                            run(3, G, 0, 3), run(1, B, 0, 5), run(2, B, 0, 3),
                                            run(2, R, 0, 5), run(3, R, 0, 5)}}},
    {11,
     5,
     0x03,
     1,
     false,
     10,
     {10, 10, 10},
     {{run(0, R, 0, 9), run(0, G, 0, 9), run(0, B, 0, 9), run(1, R, 0, 9), run(1, G, 0, 9),
       run(1, B, 0, 9)}}},
    {12,
     5,
     0x07,
     1,
     true,
     11,
     {9, 9, 9},
     {{run(0, R, 0, 9), run(0, G, 0, 9), run(0, B, 0, 9), run(1, R, 0, 8), bit(0, R, 10), run(1, G, 0, 8),
       bit(0, G, 10), run(1, B, 0, 8), bit(0, B, 10)}}},
    {13,
     5,
     0x0B,
     1,
     true,
     12,
     {8, 8, 8},
     {{run(0, R, 0, 9), run(0, G, 0, 9), run(0, B, 0, 9), run(1, R, 0, 7), run(0, R, 11, 10), run(1, G, 0, 7),
       run(0, G, 11, 10), run(1, B, 0, 7), run(0, B, 11, 10)}}},
    {14,
     5,
     0x0F,
     1,
     true,
     16,
     {4, 4, 4},
     {{run(0, R, 0, 9), run(0, G, 0, 9), run(0, B, 0, 9), run(1, R, 0, 3), run(0, R, 15, 10), run(1, G, 0, 3),
       run(0, G, 15, 10), run(1, B, 0, 3), run(0, B, 15, 10)}}},
}};

// The mode of a block's first bits, or nullptr for the reserved codes (10011, 10111, 11011, 11111), which
// decode to 0 (D3D11 "BC6H format": "reserved ... return 0 for all texels").
inline const Mode* modeOfBlock(std::uint8_t firstByte) {
    const int two = firstByte & 0x3;
    for (const Mode& m : kModes)
        if ((m.modeBits == 2 && two == m.code) ||
            (m.modeBits == 5 && two >= 2 && (firstByte & 0x1F) == m.code))
            return &m;
    return nullptr;
}

// Partition sets for two regions (the first 32 of BC7's): bit i of kPartitions[p] is texel i's region.
inline constexpr std::array<std::uint16_t, 32> kPartitions = {
    0xCCCC, 0x8888, 0xEEEE, 0xECC8, 0xC880, 0xFEEC, 0xFEC8, 0xEC80, 0xC800, 0xFFEC, 0xFE80,
    0xE800, 0xFFE8, 0xFF00, 0xFFF0, 0xF000, 0xF710, 0x008E, 0x7100, 0x08CE, 0x008C, 0x7310,
    0x3100, 0x8CCE, 0x088C, 0x3110, 0x6666, 0x366C, 0x17E8, 0x0FF0, 0x718E, 0x399C};
// The second region's anchor texel (its index has one bit less); region 0's is texel 0.
inline constexpr std::array<std::uint8_t, 32> kAnchor2 = {15, 15, 15, 15, 15, 15, 15, 15, 15, 15, 15,
                                                          15, 15, 15, 15, 15, 15, 2,  8,  2,  2,  8,
                                                          8,  15, 2,  8,  2,  2,  8,  8,  2,  2};

inline int regionOf(int partition, int texel) {
    return (kPartitions[std::size_t(partition)] >> texel) & 1;
}

inline constexpr std::array<int, 8> kWeights3 = {0, 9, 18, 27, 37, 46, 55, 64};
inline constexpr std::array<int, 16> kWeights4 = {0,  4,  9,  13, 17, 21, 26, 30,
                                                  34, 38, 43, 47, 51, 55, 60, 64};

// "unquantize" (unsigned): an endpoint of `bits` bits to the 16-bit interpolation domain.
inline int unquantize(int value, int bits) {
    if (bits >= 15) return value;
    if (value == 0) return 0;
    if (value == (1 << bits) - 1) return 0xFFFF;
    return ((value << 16) + 0x8000) >> bits;
}

// The interpolated value between two unquantized endpoints, weight w of 64.
inline int interpolate(int a, int b, int weight) {
    return (a * (64 - weight) + b * weight + 32) >> 6;
}

// "finish_unquantize" (unsigned): the interpolated value to the half's bits, 0..0x7BFF.
inline int finishUnquantize(int value) {
    return (value * 31) >> 6;
}

// Bit access to a block as two little-endian 64-bit words.
struct Bits128 {
    std::uint64_t word[2] = {0, 0};
    int get(int position) const { return int((word[position >> 6] >> (position & 63)) & 1u); }
    void set(int position, int value) {
        if (value) word[position >> 6] |= std::uint64_t(1) << (position & 63);
    }
};

} // namespace ibl::bc6h
