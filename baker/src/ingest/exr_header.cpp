// The OpenEXR header walked before OpenImageIO opens the file. OpenEXR 3.1 takes memory while it reads a
// header, sized by what the header claims, before any caller can look: a string attribute's value (a
// 1.3 KB file claiming a 1.8 GB "Software" string, found by fuzz/image_header.cpp), a string vector's
// strings, a preview image's pixels, the chunk-offset table (dataWindow with compression or tiles,
// chunkCount), and when it opens a part, one decoding buffer per chunk sized from the tile or the block
// of scanlines times the bytes of a pixel (the channel list). Each claim is held against what the file
// can hold and against the pixel limit, so such a file is refused in one line.
// Layout (OpenEXR "File Layout"): magic 76 2f 31 01, a 4-byte version with flags, then one header (a
// multi-part file: several, closed by an empty one) of attributes name\0 type\0 int32 size, value; a
// header ends with an empty name. Integers are little-endian.
#include "ingest_internal.h"

#include "iblbake/core/error.h"
#include "iblbake/core/input_file.h"
#include "iblbake/core/limits.h"

#include <algorithm>
#include <array>
#include <cstring>

namespace ibl::ingest {

namespace {

constexpr std::uint32_t kMultiPartFlag = 0x1000;
constexpr std::uint32_t kLongNamesFlag = 0x400; // names of up to 255 bytes, else 31

// Sequential reads of the open file, counting what is left of it.
class HeaderReader {
  public:
    HeaderReader(InputFile& in, const std::string& name) : in_(in), name_(name) {}

    std::size_t maxNameBytes = 31;

    std::uint64_t left() const { return in_.size() - position_; }

    void bytes(char* out, std::size_t n) {
        for (std::size_t got = 0; got < n;) {
            const std::size_t step = in_.read(out + got, n - got);
            if (step == 0) throw damaged("the file ends inside the header");
            got += step;
        }
        position_ += n;
    }
    void skip(std::uint64_t n) {
        char scratch[4096];
        for (; n > 0; n -= std::min<std::uint64_t>(n, sizeof scratch))
            bytes(scratch, std::size_t(std::min<std::uint64_t>(n, sizeof scratch)));
    }
    std::int32_t int32() {
        unsigned char b[4];
        bytes(reinterpret_cast<char*>(b), 4);
        return std::int32_t(std::uint32_t(b[0]) | std::uint32_t(b[1]) << 8 | std::uint32_t(b[2]) << 16 |
                            std::uint32_t(b[3]) << 24);
    }
    // A NUL-terminated name ("" for the NUL closing a header).
    std::string text() {
        std::string out;
        for (char c; bytes(&c, 1), c != '\0';)
            if ((out += c).size() > maxNameBytes)
                throw damaged("a name longer than " + std::to_string(maxNameBytes) + " bytes");
        return out;
    }
    Error damaged(const std::string& why) const { return Error(name_ + ": damaged OpenEXR header: " + why); }

  private:
    InputFile& in_;
    const std::string& name_;
    std::uint64_t position_ = 0;
};

// The bytes OpenEXR reads for a value of a fixed-size type, whatever size the file gives it (0: a type
// whose reader follows the size or the value's own structure: string, stringvector, chlist, preview, ...). A
// size that differs would put OpenEXR's reading somewhere else than this walk, so it is refused.
std::int32_t fixedSizeOf(const std::string& type) {
    static const std::array<std::pair<const char*, std::int32_t>, 24> sizes = {{
        {"box2i", 16},
        {"box2f", 16},
        {"chromaticities", 32},
        {"compression", 1},
        {"deepImageState", 1},
        {"double", 8},
        {"envmap", 1},
        {"float", 4},
        {"int", 4},
        {"keycode", 28},
        {"lineOrder", 1},
        {"m33f", 36},
        {"m33d", 72},
        {"m44f", 64},
        {"m44d", 128},
        {"rational", 8},
        {"tiledesc", 9},
        {"timecode", 8},
        {"v2i", 8},
        {"v2f", 8},
        {"v2d", 16},
        {"v3i", 12},
        {"v3f", 12},
        {"v3d", 24},
    }};
    for (const auto& [name, size] : sizes)
        if (type == name) return size;
    return 0;
}

// What a part's header says about its chunks. When OpenEXR opens a part it allocates one 8-byte offset
// per chunk (a file that holds the part holds those offsets after its headers) and decoding buffers of
// one chunk each: a tile, or a block of scanlines, times the bytes of a pixel.
struct PartClaims {
    std::uint64_t width = 0, height = 0; // of the dataWindow, 0 when absent or empty
    int compression = -1;
    std::uint64_t tileWidth = 0, tileHeight = 0; // of tiledesc, 0 when absent
    std::uint64_t bytesPerPixel = 0;             // of all channels in the chlist, subsampling ignored

    bool tiled() const { return tileWidth > 0 && tileHeight > 0; }

    // Scanlines per chunk (OpenEXR "Chunk Offset Tables"), by compression; an unknown compression, which
    // OpenEXR refuses, counts as the tallest.
    std::uint64_t linesPerChunk() const {
        static constexpr std::uint64_t kLinesPerChunk[] = {1, 1, 1, 16, 32, 16, 32, 32, 32, 256};
        const bool known = compression >= 0 && compression < int(std::size(kLinesPerChunk));
        return known ? kLinesPerChunk[compression] : 256;
    }
    // Chunks of level 0: tiles, or blocks of linesPerChunk() scanlines.
    std::uint64_t minimumChunks() const {
        if (width == 0 || height == 0) return 0;
        const auto divUp = [](std::uint64_t a, std::uint64_t b) { return (a + b - 1) / b; };
        if (tiled()) return divUp(width, tileWidth) * divUp(height, tileHeight);
        return divUp(height, linesPerChunk());
    }
    // Pixels of the largest chunk: a whole tile (a tile larger than the data window still takes its full
    // buffer), or the scanlines of one block.
    std::uint64_t chunkPixels() const {
        return tiled() ? tileWidth * tileHeight : width * std::min(height, linesPerChunk());
    }
};

// One attribute's value, walked as OpenEXR reads it and checked where OpenEXR sizes memory from it.
void checkAttribute(HeaderReader& in, const std::string& attribute, const std::string& type,
                    std::int32_t size, const std::string& name, PartClaims& part) {
    const std::string quoted = printableForMessage(attribute);
    if (size < 0 || std::uint64_t(size) > in.left())
        throw in.damaged("attribute " + quoted + " claims " + std::to_string(size) + " bytes, the file has " +
                         std::to_string(in.left()) + " left");
    const auto sizeMismatch = [&] {
        return in.damaged("attribute " + quoted + " of type " + printableForMessage(type) + " has " +
                          std::to_string(size) + " bytes, which is not the size of its value");
    };
    if (const std::int32_t fixed = fixedSizeOf(type); fixed > 0 && size != fixed) throw sizeMismatch();
    if (attribute == "dataWindow" && type == "box2i") {
        const std::int64_t xMin = in.int32(), yMin = in.int32(), xMax = in.int32(), yMax = in.int32();
        // An empty or inverted window is OpenEXR's to refuse; it takes no memory for one.
        if (xMax >= xMin && yMax >= yMin) {
            part.width = std::uint64_t(xMax - xMin + 1), part.height = std::uint64_t(yMax - yMin + 1);
            checkPixelLimit(name, part.width, part.height);
        }
    } else if (attribute == "compression" && type == "compression") {
        unsigned char compression;
        in.bytes(reinterpret_cast<char*>(&compression), 1);
        part.compression = compression;
    } else if (attribute == "tiles" && type == "tiledesc") {
        part.tileWidth = std::uint32_t(in.int32()), part.tileHeight = std::uint32_t(in.int32());
        in.skip(1); // the level mode: more levels add chunks, the bound holds without them
    } else if (attribute == "chunkCount" && type == "int") {
        // One 8-byte offset per chunk follows the headers: a count the file cannot hold is a lie.
        const std::int64_t chunks = in.int32();
        if (chunks < 0 || std::uint64_t(chunks) > in.left() / 8)
            throw in.damaged("chunkCount " + std::to_string(chunks) + " is more than the file can hold");
    } else if (type == "chlist") {
        // Channels (name\0, then pixel type int32, pLinear, 3 reserved bytes, x and y sampling int32) up to
        // an empty name, which must end the attribute. HALF (1) is 2 bytes, UINT (0) and FLOAT (2) are 4.
        std::int64_t left = size;
        for (;;) {
            const std::string channel = in.text();
            left -= std::int64_t(channel.size()) + 1;
            if (channel.empty()) break;
            if (left < 16) throw sizeMismatch();
            const std::int32_t pixelType = in.int32();
            if (attribute == "channels") part.bytesPerPixel += pixelType == 1 ? 2 : 4;
            in.skip(12);
            left -= 16;
        }
        if (left != 0) throw sizeMismatch();
    } else if (type == "preview") {
        // width, height, then width x height RGBA bytes: the attribute's size exactly.
        if (size < 8) throw sizeMismatch();
        const std::uint64_t width = std::uint32_t(in.int32()), height = std::uint32_t(in.int32());
        const std::uint64_t pixelBytes = std::uint64_t(size) - 8;
        if ((width > 0 && height > pixelBytes / 4 / width) || width * height * 4 != pixelBytes)
            throw in.damaged("the preview claims " + std::to_string(width) + "x" + std::to_string(height) +
                             " pixels, not what its " + std::to_string(size) + " bytes hold");
        in.skip(std::uint64_t(size) - 8);
    } else if (type == "stringvector") {
        // int32 length, then that many bytes, until the attribute's size is used up.
        for (std::int64_t left = size; left > 0;) {
            const std::int64_t length = left >= 4 ? in.int32() : -1;
            left -= 4;
            if (length < 0 || length > left)
                throw in.damaged("a string of " + quoted + " runs past the attribute's " +
                                 std::to_string(size) + " bytes");
            in.skip(std::uint64_t(length));
            left -= length;
        }
    } else if (type == "floatvector" && size % 4 != 0) {
        throw sizeMismatch();
    } else {
        in.skip(std::uint64_t(size));
    }
}

// A chunk's decoding buffer is held to the memory the pixel limit allows a whole image in memory (an
// ImageRGBA pixel each) and a tile to the pixel limit itself: found by fuzz/image_header.cpp, a 4096-pixel
// data window tiled in tiles of billions of pixels, whose tile buffer OpenEXR allocated on open.
void checkChunkBuffers(const HeaderReader& in, const PartClaims& part) {
    const std::uint64_t maxPixels = limits::maxImagePixels();
    if (part.tiled() && part.tileHeight > maxPixels / part.tileWidth)
        throw in.damaged("its " + std::to_string(part.tileWidth) + "x" + std::to_string(part.tileHeight) +
                         " tiles are larger than the limit of " + std::to_string(maxPixels) + " pixels (" +
                         limits::kMaxImagePixelsVariable + ")");
    constexpr std::uint64_t kBudgetBytesPerPixel = sizeof(decltype(ImageRGBA::pixels)::value_type);
    const std::uint64_t chunkPixels = part.chunkPixels(); // at most 2^40 x 256: no overflow
    if (part.bytesPerPixel > 0 && chunkPixels > maxPixels * kBudgetBytesPerPixel / part.bytesPerPixel)
        throw in.damaged("a chunk of " + std::to_string(chunkPixels) + " pixels of " +
                         std::to_string(part.bytesPerPixel) + " bytes is more than the " +
                         std::to_string(maxPixels * kBudgetBytesPerPixel) +
                         " bytes the pixel limit allows (" + limits::kMaxImagePixelsVariable + ")");
}

} // namespace

void checkExrHeader(const std::filesystem::path& file, const std::string& name) {
    InputFile input(file);
    HeaderReader in(input, name);
    if (in.left() < 8) return; // not OpenEXR, or too short for OpenEXR to take anything
    char magic[4];
    in.bytes(magic, 4);
    if (std::memcmp(magic, "\x76\x2f\x31\x01", 4) != 0) return;
    const std::uint32_t flags = std::uint32_t(in.int32());
    const bool multiPart = (flags & kMultiPartFlag) != 0;
    if (flags & kLongNamesFlag) in.maxNameBytes = 255;
    for (int part = 0;; ++part) {
        std::string attribute = in.text();
        if (attribute.empty()) {
            if (!multiPart || part > 0) return; // the single header's end, or the empty header after the last
            throw in.damaged("a multi-part file with no part");
        }
        PartClaims claims;
        for (; !attribute.empty(); attribute = in.text()) {
            const std::string type = in.text();
            checkAttribute(in, attribute, type, in.int32(), name, claims);
        }
        if (const std::uint64_t chunks = claims.minimumChunks(); chunks > in.left() / 8)
            throw in.damaged("its " + std::to_string(claims.width) + "x" + std::to_string(claims.height) +
                             " data window needs " + std::to_string(chunks) +
                             " chunk offsets, more than the rest of the file holds");
        checkChunkBuffers(in, claims);
        if (!multiPart) return;
    }
}

} // namespace ibl::ingest
