// Facts about the KTX2 container and the formats iblbake stores, shared by the writer and the reader
// so that both agree on one table. Section names refer to the KTX 2.0 specification (Khronos) and to the
// Khronos Data Format Specification (KDF).
#pragma once

#include "bc6h.h"
#include "iblbake/ktx2/ktx2.h"

#include <array>
#include <cstdint>
#include <cstring>
#include <optional>
#include <vector>

namespace ibl::ktx2 {

// KTX 2.0 "identifier": «KTX 20»\r\n\x1A\n.
inline constexpr std::array<std::uint8_t, 12> kIdentifier = {0xAB, 0x4B, 0x54, 0x58, 0x20, 0x32,
                                                             0x30, 0xBB, 0x0D, 0x0A, 0x1A, 0x0A};
inline constexpr std::size_t kHeaderBytes = 80;          // identifier, 9 UInt32 fields, then the Index
inline constexpr std::size_t kLevelIndexEntryBytes = 24; // byteOffset, byteLength, uncompressedByteLength

// KDF basic descriptor block constants (KDF section 5).
inline constexpr std::uint32_t kDfVersion = 2;              // versionNumber of KDF 1.3 and later
inline constexpr std::uint32_t kModelRgbsda = 1;            // KHR_DF_MODEL_RGBSDA
inline constexpr std::uint32_t kModelBc6h = 131;            // KHR_DF_MODEL_BC6H
inline constexpr std::uint32_t kPrimariesBt709 = 1;         // KHR_DF_PRIMARIES_BT709
inline constexpr std::uint32_t kTransferLinear = 1;         // KHR_DF_TRANSFER_LINEAR
inline constexpr std::uint32_t kFlagAlphaPremultiplied = 1; // KHR_DF_FLAG_ALPHA_PREMULTIPLIED
inline constexpr std::uint8_t kQualifierLinear = 0x10;
inline constexpr std::uint8_t kQualifierExponent = 0x20;
inline constexpr std::uint8_t kQualifierSigned = 0x40;
inline constexpr std::uint8_t kQualifierFloat = 0x80;
inline constexpr std::uint8_t kChannelR = 0, kChannelG = 1, kChannelB = 2, kChannelA = 15;

struct FormatInfo {
    Ktx2Format format;
    std::uint32_t vkFormat;
    std::uint32_t dxgiFormat; // the DDS container's DXGI_FORMAT (dds_writer.cpp)
    std::uint32_t typeSize;   // KTX 2.0 "typeSize": component size, 4 for the *_PACK32 formats, 1 for blocks
    std::uint32_t texelBytes; // Vulkan texel block size (also the DFD's bytesPlane0)
    std::uint32_t blockSize;  // texels a block spans in x and in y: 1, or 4 for BC6H
    bool hasAlpha;
    bc6h::Preset preset; // the BC6H encoder's effort (BC6H formats only)
};

// One table for every format. DXGI: R16G16B16A16_FLOAT 10, R32G32B32A32_FLOAT 2, R11G11B10_FLOAT 26 and
// R9G9B9E5_SHAREDEXP 67 (the same bits as their Vulkan formats), BC6H_UF16 95.
inline constexpr std::array<FormatInfo, 7> kFormats = {{
    {Ktx2Format::RGBA16F, 97, 10, 2, 8, 1, true, bc6h::Preset::Default},
    {Ktx2Format::RGBA32F, 109, 2, 4, 16, 1, true, bc6h::Preset::Default},
    {Ktx2Format::B10G11R11, 122, 26, 4, 4, 1, false, bc6h::Preset::Default},
    {Ktx2Format::E5B9G9R9, 123, 67, 4, 4, 1, false, bc6h::Preset::Default},
    {Ktx2Format::BC6H, 131, 95, 1, 16, 4, false, bc6h::Preset::Default},
    {Ktx2Format::BC6HFast, 131, 95, 1, 16, 4, false, bc6h::Preset::Fast},
    {Ktx2Format::BC6HBest, 131, 95, 1, 16, 4, false, bc6h::Preset::Best},
}};

inline const FormatInfo& formatInfo(Ktx2Format format) {
    for (const FormatInfo& f : kFormats)
        if (f.format == format) return f;
    return kFormats[0]; // unreachable for valid enumerators
}

inline std::optional<FormatInfo> findFormat(std::uint32_t vkFormat) {
    for (const FormatInfo& f : kFormats)
        if (f.vkFormat == vkFormat) return f;
    return std::nullopt;
}

// KTX 2.0 "mipPadding": level data starts at a multiple of lcm(texel block size, 4). The block sizes here
// are 4, 8 and 16, so the lcm is simply max(size, 4).
inline std::uint32_t levelAlignment(const FormatInfo& f) {
    return f.texelBytes < 4 ? 4 : f.texelBytes;
}

// The bytes of one image of width x height texels: whole blocks (a level below the block size is one block
// wide or high, KTX 2.0 "Level Index"). Saturates at UINT64_MAX.
inline std::uint64_t imageBytes(const FormatInfo& f, std::uint64_t width, std::uint64_t height) {
    const std::uint64_t blocksX = (width + f.blockSize - 1) / f.blockSize;
    const std::uint64_t blocksY = (height + f.blockSize - 1) / f.blockSize;
    std::uint64_t bytes = blocksX;
    for (std::uint64_t factor : {blocksY, std::uint64_t(f.texelBytes)})
        if (__builtin_mul_overflow(bytes, factor, &bytes)) return UINT64_MAX;
    return bytes;
}

inline std::uint32_t floatBits(float v) {
    std::uint32_t u;
    std::memcpy(&u, &v, sizeof u);
    return u;
}

struct Sample {
    std::uint32_t bitOffset;
    std::uint32_t bitLength;  // the real length; stored as length - 1
    std::uint8_t channelType; // channel id | qualifier bits
    std::uint32_t lower;
    std::uint32_t upper;
};

// The samples the KDF format tables define for each vkFormat (KDF "Vulkan format" descriptors):
// float formats use the bit patterns of -1.0f/0.0f and 1.0f as sampleLower/sampleUpper; E5B9G9R9 has an
// unsigned 9-bit mantissa sample (upper 8448) followed by the shared 5-bit exponent sample (EXPONENT
// qualifier, lower = bias 15, upper = 31) for each of R, G, B. BC6H (KDF "BC6H", unsigned) is one 128-bit
// sample of channel KHR_DF_CHANNEL_BC6H_COLOR (0) with the FLOAT qualifier, 0.0 to 1.0.
inline std::vector<Sample> formatSamples(Ktx2Format format) {
    const std::uint32_t minusOne = floatBits(-1.0f), zero = floatBits(0.0f), one = floatBits(1.0f);
    const std::uint8_t sfloat = kQualifierFloat | kQualifierSigned;
    switch (format) {
    case Ktx2Format::RGBA16F:
        return {{0, 16, std::uint8_t(kChannelR | sfloat), minusOne, one},
                {16, 16, std::uint8_t(kChannelG | sfloat), minusOne, one},
                {32, 16, std::uint8_t(kChannelB | sfloat), minusOne, one},
                {48, 16, std::uint8_t(kChannelA | sfloat), minusOne, one}};
    case Ktx2Format::RGBA32F:
        return {{0, 32, std::uint8_t(kChannelR | sfloat), minusOne, one},
                {32, 32, std::uint8_t(kChannelG | sfloat), minusOne, one},
                {64, 32, std::uint8_t(kChannelB | sfloat), minusOne, one},
                {96, 32, std::uint8_t(kChannelA | sfloat), minusOne, one}};
    case Ktx2Format::B10G11R11:
        return {{0, 11, std::uint8_t(kChannelR | kQualifierFloat), zero, one},
                {11, 11, std::uint8_t(kChannelG | kQualifierFloat), zero, one},
                {22, 10, std::uint8_t(kChannelB | kQualifierFloat), zero, one}};
    case Ktx2Format::E5B9G9R9:
        return {{0, 9, kChannelR, 0, 8448},  {27, 5, std::uint8_t(kChannelR | kQualifierExponent), 15, 31},
                {9, 9, kChannelG, 0, 8448},  {27, 5, std::uint8_t(kChannelG | kQualifierExponent), 15, 31},
                {18, 9, kChannelB, 0, 8448}, {27, 5, std::uint8_t(kChannelB | kQualifierExponent), 15, 31}};
    case Ktx2Format::BC6H:
    case Ktx2Format::BC6HFast:
    case Ktx2Format::BC6HBest:
        return {{0, 128, kQualifierFloat, zero, one}};
    }
    return {};
}

// The complete Data Format Descriptor as UInt32 words: dfdTotalSize, then one basic descriptor block
// (KDF section 5: vendorId/descriptorType, versionNumber/descriptorBlockSize, model/primaries/transfer/
// flags, texelBlockDimension0..3, bytesPlane0..7, then 4 words per sample).
inline std::vector<std::uint32_t> dataFormatDescriptor(Ktx2Format format, Ktx2Alpha alpha) {
    const FormatInfo& info = formatInfo(format);
    const std::vector<Sample> samples = formatSamples(format);
    const std::uint32_t blockBytes = 24 + 16 * std::uint32_t(samples.size());
    std::vector<std::uint32_t> words;
    words.push_back(4 + blockBytes);
    words.push_back(0); // vendorId KHRONOS (0), descriptorType BASICFORMAT (0)
    words.push_back(kDfVersion | (blockBytes << 16));
    const std::uint32_t flags = alpha == Ktx2Alpha::Premultiplied ? kFlagAlphaPremultiplied : 0;
    const std::uint32_t model = info.blockSize > 1 ? kModelBc6h : kModelRgbsda;
    words.push_back(model | (kPrimariesBt709 << 8) | (kTransferLinear << 16) | (flags << 24));
    // texelBlockDimension0..3, each stored minus one: 1x1x1x1, or 4x4x1x1 for BC6H.
    words.push_back((info.blockSize - 1) | ((info.blockSize - 1) << 8));
    words.push_back(info.texelBytes); // bytesPlane0; planes 1..3 unused
    words.push_back(0);               // bytesPlane4..7
    for (const Sample& s : samples) {
        words.push_back(s.bitOffset | ((s.bitLength - 1) << 16) | (std::uint32_t(s.channelType) << 24));
        words.push_back(0); // samplePosition0..3: the texel origin
        words.push_back(s.lower);
        words.push_back(s.upper);
    }
    return words;
}

} // namespace ibl::ktx2
