// KTX 2.0 reader for the formats of ktx2_format.h. A file is untrusted input: every offset and length is
// checked against the file size (with 64-bit arithmetic that cannot overflow) before anything is read or
// allocated, so the largest allocation is bounded by a small multiple of the file size. The file is read
// whole and parsed from memory, which is also the entry point of the fuzz target (fuzz/ktx2_reader.cpp).
#include "iblbake/core/error.h"
#include "iblbake/ktx2/cube_profile.h"
#include "iblbake/ktx2/ktx2.h"
#include "ktx2_format.h"
#include "small_float.h"

#include <algorithm>
#include <bit>
#include <climits>
#include <fstream>
#include <span>

namespace ibl {

namespace {

namespace fs = std::filesystem;
using ktx2::FormatInfo;

// Bounds-checked little-endian reads from a byte buffer; running past the end is a damaged file.
class ByteSource {
  public:
    ByteSource(std::span<const std::uint8_t> bytes, const std::string& name, const char* section)
        : bytes_(bytes), name_(name), section_(section) {}
    std::uint32_t u32() { return std::uint32_t(take(4)); }
    std::uint64_t u64() { return take(8); }
    void skip(std::size_t n) { pos_ += checked(n); }
    std::size_t position() const { return pos_; }
    std::size_t remaining() const { return bytes_.size() - pos_; }

  private:
    std::size_t checked(std::size_t n) const {
        if (remaining() < n) throw Error(name_ + ": " + section_ + " ends early");
        return n;
    }
    std::uint64_t take(std::size_t n) {
        checked(n);
        std::uint64_t v = 0;
        for (std::size_t i = 0; i < n; ++i)
            v |= std::uint64_t(bytes_[pos_ + i]) << (8 * i);
        pos_ += n;
        return v;
    }
    std::span<const std::uint8_t> bytes_;
    const std::string& name_;
    const char* section_;
    std::size_t pos_ = 0;
};

std::vector<std::uint8_t> readWholeFile(const fs::path& path, const std::string& name) {
    std::error_code ec;
    if (!fs::exists(path, ec)) throw Error(name + ": no such file");
    if (!fs::is_regular_file(path, ec)) throw Error(name + ": not a regular file");
    const std::uintmax_t size = fs::file_size(path, ec);
    if (ec) throw Error(name + ": cannot determine the file size: " + ec.message());
    std::ifstream in(path, std::ios::binary);
    if (!in) throw Error(name + ": cannot open for reading");
    std::vector<std::uint8_t> bytes(size);
    in.read(reinterpret_cast<char*>(bytes.data()), std::streamsize(size));
    if (!in || std::uintmax_t(in.gcount()) != size) throw Error(name + ": cannot read the file");
    return bytes;
}

// The bytes [offset, offset + length) of the file; the caller has already checked that range.
std::span<const std::uint8_t> slice(std::span<const std::uint8_t> file, std::uint64_t offset,
                                    std::uint64_t length) {
    return file.subspan(std::size_t(offset), std::size_t(length));
}

// True when [offset, offset + length) lies inside a file of `fileSize` bytes.
bool inside(std::uint64_t offset, std::uint64_t length, std::uint64_t fileSize) {
    return offset <= fileSize && length <= fileSize - offset;
}

struct Header {
    std::uint32_t vkFormat, typeSize, pixelWidth, pixelHeight, pixelDepth, layerCount, faceCount, levelCount,
        supercompressionScheme, dfdByteOffset, dfdByteLength, kvdByteOffset, kvdByteLength;
    std::uint64_t sgdByteOffset, sgdByteLength;
};

struct LevelEntry {
    std::uint64_t byteOffset, byteLength, uncompressedByteLength;
};

Header parseHeader(std::span<const std::uint8_t> bytes, const std::string& name) {
    if (!std::equal(ktx2::kIdentifier.begin(), ktx2::kIdentifier.end(), bytes.begin()))
        throw Error(name + ": not a KTX 2.0 file (wrong identifier)");
    ByteSource in(bytes, name, "header");
    in.skip(ktx2::kIdentifier.size());
    Header h{};
    h.vkFormat = in.u32();
    h.typeSize = in.u32();
    h.pixelWidth = in.u32();
    h.pixelHeight = in.u32();
    h.pixelDepth = in.u32();
    h.layerCount = in.u32();
    h.faceCount = in.u32();
    h.levelCount = in.u32();
    h.supercompressionScheme = in.u32();
    h.dfdByteOffset = in.u32();
    h.dfdByteLength = in.u32();
    h.kvdByteOffset = in.u32();
    h.kvdByteLength = in.u32();
    h.sgdByteOffset = in.u64();
    h.sgdByteLength = in.u64();
    return h;
}

// Texture type and format checks (KTX 2.0 "Texture Type", "typeSize", "levelCount",
// "supercompressionScheme"), restricted to what iblbake supports: 2D textures, 2D arrays and cube maps (no
// cube arrays).
FormatInfo checkHeader(const Header& h, const std::string& name) {
    const auto info = ktx2::findFormat(h.vkFormat);
    if (!info) throw Error(name + ": unsupported vkFormat " + std::to_string(h.vkFormat));
    if (h.typeSize != info->typeSize)
        throw Error(name + ": typeSize " + std::to_string(h.typeSize) + " does not match vkFormat " +
                    std::to_string(h.vkFormat));
    if (h.pixelWidth == 0 || h.pixelHeight == 0)
        throw Error(name + ": 1D or empty textures are not supported");
    if (h.pixelWidth > INT_MAX || h.pixelHeight > INT_MAX) throw Error(name + ": image size is too large");
    if (h.pixelDepth != 0) throw Error(name + ": 3D textures are not supported");
    if (h.layerCount > 4096)
        throw Error(name + ": layerCount " + std::to_string(h.layerCount) + " exceeds 4096");
    if (h.faceCount != 1 && h.faceCount != 6)
        throw Error(name + ": faceCount " + std::to_string(h.faceCount) + " is neither 1 nor 6");
    if (h.faceCount == 6 && h.pixelWidth != h.pixelHeight)
        throw Error(name + ": cube map faces are not square");
    if (h.supercompressionScheme != 0)
        throw Error(name + ": supercompression scheme " + std::to_string(h.supercompressionScheme) +
                    " is not supported");
    const std::uint32_t maxLevels = std::uint32_t(std::bit_width(std::max(h.pixelWidth, h.pixelHeight)));
    if (h.levelCount > maxLevels)
        throw Error(name + ": levelCount " + std::to_string(h.levelCount) + " exceeds the maximum " +
                    std::to_string(maxLevels) + " for this size");
    if (h.sgdByteLength != 0 || h.sgdByteOffset != 0)
        throw Error(name + ": supercompression global data present without supercompression");
    return *info;
}

// The DFD must hold a basic descriptor block whose layout and samples are exactly those of vkFormat
// (KTX 2.0 "Data Format Descriptor" restrictions; only the LINEAR qualifier bit may differ). Colour
// primaries are informational and the premultiplied-alpha flag is returned; the transfer function must be
// linear, since the texels are returned as linear values.
Ktx2Alpha checkDfd(std::span<const std::uint8_t> bytes, const FormatInfo& info, const std::string& name) {
    const std::vector<std::uint32_t> expected = ktx2::dataFormatDescriptor(info.format, Ktx2Alpha::Straight);
    ByteSource in(bytes, name, "data format descriptor");
    if (in.u32() != bytes.size()) throw Error(name + ": dfdTotalSize does not match dfdByteLength");
    std::vector<std::uint32_t> block;
    for (std::size_t i = 1; i < expected.size() && in.remaining() >= 4; ++i)
        block.push_back(in.u32());
    if (block.size() + 1 != expected.size() || block[0] != 0)
        throw Error(name + ": data format descriptor has no basic descriptor block for vkFormat " +
                    std::to_string(info.vkFormat));
    const std::uint32_t blockBytes = block[1] >> 16;
    if ((block[1] & 0xFFFFu) != ktx2::kDfVersion || blockBytes != expected[2] >> 16)
        throw Error(name + ": data format descriptor block has an unexpected version or size");
    if ((block[2] & 0xFFu) != (expected[3] & 0xFFu))
        throw Error(name + ": colour model " + std::to_string(block[2] & 0xFFu) +
                    " does not match vkFormat " + std::to_string(info.vkFormat));
    if (((block[2] >> 16) & 0xFFu) != ktx2::kTransferLinear)
        throw Error(name + ": transfer function " + std::to_string((block[2] >> 16) & 0xFFu) +
                    " is not linear");
    const std::uint32_t ignoreLinearQualifier = ~(std::uint32_t(ktx2::kQualifierLinear) << 24);
    for (std::size_t i = 3; i < block.size(); ++i) {
        const bool sampleTypeWord = i >= 6 && (i - 6) % 4 == 0;
        const std::uint32_t mask = sampleTypeWord ? ignoreLinearQualifier : 0xFFFFFFFFu;
        if ((block[i] & mask) != (expected[i + 1] & mask))
            throw Error(name + ": data format descriptor does not match vkFormat " +
                        std::to_string(info.vkFormat));
    }
    return (block[2] >> 24) & ktx2::kFlagAlphaPremultiplied ? Ktx2Alpha::Premultiplied : Ktx2Alpha::Straight;
}

// KTX 2.0 "Key/Value Data": the entries must exactly fill kvdByteLength, keys must be non-empty,
// NUL-terminated, sorted and unique.
std::map<std::string, std::string> parseKeyValues(std::span<const std::uint8_t> bytes,
                                                  const std::string& name) {
    std::map<std::string, std::string> result;
    ByteSource in(bytes, name, "key/value data");
    std::string previous;
    while (in.remaining() > 0) {
        const std::uint32_t length = in.u32();
        const std::size_t start = in.position();
        if (length < 2 || length > in.remaining()) throw Error(name + ": key/value entry has a bad length");
        const auto first = bytes.begin() + std::ptrdiff_t(start);
        const auto last = first + std::ptrdiff_t(length);
        const auto nul = std::find(first, last, std::uint8_t(0));
        if (nul == last || nul == first) throw Error(name + ": key/value entry has no NUL-terminated key");
        std::string key(first, nul);
        std::string value(nul + 1, last);
        if (!value.empty() && value.back() == '\0') value.pop_back();
        if (!result.empty() && !(previous < key))
            throw Error(name + ": key/value data is not sorted by unique keys at " + quotedForMessage(key));
        const std::size_t padded = (std::size_t(length) + 3) / 4 * 4;
        if (padded > in.remaining()) throw Error(name + ": key/value data ends inside an entry's padding");
        in.skip(padded);
        previous = key;
        result.emplace(std::move(key), std::move(value));
    }
    return result;
}

// Saturates at UINT64_MAX on overflow: no file is that large, so such a level fails the bounds check.
std::uint64_t levelByteLength(const Header& h, const FormatInfo& info, std::uint32_t level) {
    const std::uint64_t width = std::max<std::uint64_t>(1, h.pixelWidth >> level);
    const std::uint64_t height = std::max<std::uint64_t>(1, h.pixelHeight >> level);
    std::uint64_t bytes = ktx2::imageBytes(info, width, height);
    for (std::uint64_t factor : {std::uint64_t(h.faceCount), std::uint64_t(std::max(1u, h.layerCount))})
        if (__builtin_mul_overflow(bytes, factor, &bytes)) return UINT64_MAX;
    return bytes;
}

glm::vec4 decodeTexel(const std::uint8_t* p, Ktx2Format format) {
    auto u16 = [&](int i) { return std::uint16_t(p[2 * i] | (p[2 * i + 1] << 8)); };
    auto u32 = [&](int i) {
        return std::uint32_t(p[4 * i]) | (std::uint32_t(p[4 * i + 1]) << 8) |
               (std::uint32_t(p[4 * i + 2]) << 16) | (std::uint32_t(p[4 * i + 3]) << 24);
    };
    glm::vec4 v(0.0f, 0.0f, 0.0f, 1.0f);
    switch (format) {
    case Ktx2Format::RGBA16F:
        for (int c = 0; c < 4; ++c)
            v[c] = smallfloat::halfToFloat(u16(c));
        break;
    case Ktx2Format::RGBA32F:
        for (int c = 0; c < 4; ++c) {
            const std::uint32_t bits = u32(c);
            std::memcpy(&v[c], &bits, sizeof bits);
        }
        break;
    case Ktx2Format::B10G11R11:
        smallfloat::unpackB10G11R11(u32(0), v.r, v.g, v.b);
        break;
    case Ktx2Format::E5B9G9R9:
        smallfloat::unpackE5B9G9R9(u32(0), v.r, v.g, v.b);
        break;
    default: // block formats are decoded a whole image at a time
        break;
    }
    return v;
}

} // namespace

Ktx2Image readKtx2(const fs::path& path) {
    const std::string name = path.string();
    return parseKtx2(readWholeFile(path, name), name);
}

Ktx2Image parseKtx2(std::span<const std::uint8_t> file, const std::string& name) {
    const std::uint64_t fileSize = file.size();
    if (fileSize < ktx2::kHeaderBytes)
        throw Error(name + ": too short for a KTX 2.0 header (" + std::to_string(fileSize) + " bytes)");
    const Header h = parseHeader(slice(file, 0, ktx2::kHeaderBytes), name);
    const FormatInfo info = checkHeader(h, name);

    const std::uint32_t numLevels = std::max<std::uint32_t>(1, h.levelCount);
    const std::uint64_t indexEnd =
        ktx2::kHeaderBytes + std::uint64_t(ktx2::kLevelIndexEntryBytes) * numLevels;
    if (!inside(ktx2::kHeaderBytes, indexEnd - ktx2::kHeaderBytes, fileSize))
        throw Error(name + ": file ends inside the level index");
    ByteSource index(slice(file, ktx2::kHeaderBytes, indexEnd - ktx2::kHeaderBytes), name, "level index");
    std::vector<LevelEntry> levels(numLevels);
    for (LevelEntry& e : levels)
        e = {index.u64(), index.u64(), index.u64()};

    // The DFD follows the level index without padding, the key/value data follows the DFD
    // (KTX 2.0 "File Structure", "dfdTotalSize").
    if (h.dfdByteOffset != indexEnd || h.dfdByteLength % 4 != 0 ||
        !inside(h.dfdByteOffset, h.dfdByteLength, fileSize))
        throw Error(name + ": data format descriptor does not follow the level index inside the file");
    Ktx2Image image;
    image.alpha = checkDfd(slice(file, h.dfdByteOffset, h.dfdByteLength), info, name);
    std::uint64_t metadataEnd = std::uint64_t(h.dfdByteOffset) + h.dfdByteLength;

    if (h.kvdByteLength == 0) {
        if (h.kvdByteOffset != 0) throw Error(name + ": kvdByteOffset is set for empty key/value data");
    } else {
        if (h.kvdByteOffset != metadataEnd || !inside(h.kvdByteOffset, h.kvdByteLength, fileSize))
            throw Error(name + ": key/value data does not follow the data format descriptor inside the file");
        image.keyValues = parseKeyValues(slice(file, h.kvdByteOffset, h.kvdByteLength), name);
        metadataEnd += h.kvdByteLength;
    }

    // Level Index: each level exactly the size its dimensions imply, aligned, inside the file, after the
    // metadata, and stored from the smallest level to the largest without overlap.
    const std::uint64_t alignment = ktx2::levelAlignment(info);
    for (std::uint32_t p = 0; p < numLevels; ++p) {
        const LevelEntry& e = levels[p];
        const std::string level = "level " + std::to_string(p);
        if (e.byteLength != levelByteLength(h, info, p) || e.uncompressedByteLength != e.byteLength)
            throw Error(name + ": " + level + " has a byte length that does not match its size");
        if (e.byteOffset % alignment != 0) throw Error(name + ": " + level + " is not aligned");
        if (e.byteOffset < metadataEnd || !inside(e.byteOffset, e.byteLength, fileSize))
            throw Error(name + ": " + level + " lies outside the file's image data");
        if (p > 0 && e.byteOffset + e.byteLength > levels[p - 1].byteOffset)
            throw Error(name + ": " + level + " is not stored before the larger level " +
                        std::to_string(p - 1));
    }

    image.vkFormat = h.vkFormat;
    image.pixelWidth = h.pixelWidth;
    image.pixelHeight = h.pixelHeight;
    image.faceCount = h.faceCount;
    image.layerCount = h.layerCount;
    image.levelCount = h.levelCount;
    image.levels.resize(numLevels);
    for (std::uint32_t p = 0; p < numLevels; ++p) {
        const std::span<const std::uint8_t> data = slice(file, levels[p].byteOffset, levels[p].byteLength);
        const int width = int(std::max<std::uint32_t>(1, h.pixelWidth >> p));
        const int height = int(std::max<std::uint32_t>(1, h.pixelHeight >> p));
        const std::uint8_t* cursor = data.data();
        for (std::uint32_t f = 0; f < h.faceCount * std::max(1u, h.layerCount); ++f) {
            if (info.blockSize > 1) {
                image.levels[p].push_back(bc6h::decodeImage(cursor, width, height));
                cursor += ktx2::imageBytes(info, std::uint64_t(width), std::uint64_t(height));
                continue;
            }
            ImageRGBA face(width, height);
            for (glm::vec4& texel : face.pixels) {
                texel = decodeTexel(cursor, info.format);
                cursor += info.texelBytes;
            }
            image.levels[p].push_back(std::move(face));
        }
    }
    // Every cube in the standard layout, whatever profile it was stored for (cube_profile.h).
    if (auto profile = image.keyValues.find(kCubeProfileKey);
        profile != image.keyValues.end() && h.faceCount == 6) {
        try {
            if (parseCubeProfile(profile->second) == CubeProfile::Three)
                for (std::vector<ImageRGBA>& level : image.levels)
                    for (std::size_t first = 0; first < level.size(); first += 6) // each layer's cube
                        mirrorCubeFacesX(std::span<ImageRGBA>(level).subspan(first, 6));
        } catch (const Error& e) {
            throw Error(name + ": " + kCubeProfileKey + ": " + e.what());
        }
    }
    return image;
}

} // namespace ibl
