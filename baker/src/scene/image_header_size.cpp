// imageHeaderPixels (image_header_size.h): the first 64 KB of the file, parsed without an image library.
#include "image_header_size.h"

#include "iblbake/core/input_file.h"

#include <cstdio>
#include <cstring>
#include <string>

namespace ibl {

namespace {

// Sides past 2^31 (more than any reader takes) count as unknown, so that no product of them wraps.
constexpr unsigned long kMostSide = 1ul << 31;

std::uint32_t littleEndian32(const unsigned char* at) {
    return std::uint32_t(at[0]) | std::uint32_t(at[1]) << 8 | std::uint32_t(at[2]) << 16 |
           std::uint32_t(at[3]) << 24;
}

std::uint32_t bigEndian32(const unsigned char* at) {
    return std::uint32_t(at[3]) | std::uint32_t(at[2]) << 8 | std::uint32_t(at[1]) << 16 |
           std::uint32_t(at[0]) << 24;
}

// Radiance: text lines up to an empty one, then the resolution line "-Y H +X W" (either axis first, either
// sign; Greg Ward's file format description).
std::optional<ImageHeaderSize> radianceSize(const std::string& header) {
    const std::size_t blank = header.find("\n\n");
    if (blank == std::string::npos) return std::nullopt;
    char axis0[3] = {}, axis1[3] = {};
    unsigned long size0 = 0, size1 = 0;
    if (std::sscanf(header.c_str() + blank + 2, "%2s %lu %2s %lu", axis0, &size0, axis1, &size1) != 4 ||
        size0 > kMostSide || size1 > kMostSide)
        return std::nullopt;
    const bool rowsFirst = axis0[1] == 'Y'; // "-Y H +X W": scan lines of W pixels
    return ImageHeaderSize{rowsFirst ? size1 : size0, rowsFirst ? size0 : size1, false};
}

// OpenEXR: magic, version, then attributes "name\0type\0<int32 size><value>" up to an empty name; the
// dataWindow is a box2i (xMin, yMin, xMax, yMax, int32 each).
std::optional<ImageHeaderSize> exrSize(const std::string& header) {
    const auto* bytes = reinterpret_cast<const unsigned char*>(header.data());
    std::size_t at = 8;
    while (at < header.size() && header[at] != '\0') {
        const std::size_t nameEnd = header.find('\0', at);
        if (nameEnd == std::string::npos) return std::nullopt;
        const std::size_t typeEnd = header.find('\0', nameEnd + 1);
        if (typeEnd == std::string::npos || typeEnd + 5 > header.size()) return std::nullopt;
        const std::string name = header.substr(at, nameEnd - at);
        const std::uint32_t size = littleEndian32(bytes + typeEnd + 1);
        const std::size_t value = typeEnd + 5;
        if (size > header.size() - value) return std::nullopt;
        if (name == "dataWindow" && size == 16) {
            const auto coordinate = [&](int i) {
                return std::int64_t(std::int32_t(littleEndian32(bytes + value + 4 * i)));
            };
            const std::int64_t width = coordinate(2) - coordinate(0) + 1,
                               height = coordinate(3) - coordinate(1) + 1;
            if (width < 1 || height < 1) return std::nullopt;
            return ImageHeaderSize{std::uint64_t(width), std::uint64_t(height), true};
        }
        at = value + size;
    }
    return std::nullopt;
}

} // namespace

std::optional<ImageHeaderSize> imageHeaderSize(const std::filesystem::path& file) {
    std::string header(64 * 1024, '\0');
    std::size_t filled = 0;
    try {
        InputFile in(file);
        while (filled < header.size()) {
            const std::size_t n = in.read(header.data() + filled, header.size() - filled);
            if (n == 0) break;
            filled += n;
        }
    } catch (const std::exception&) { // the bake names what is wrong with the file
        return std::nullopt;
    }
    header.resize(filled);
    const auto* bytes = reinterpret_cast<const unsigned char*>(header.data());
    if (header.rfind("#?", 0) == 0) return radianceSize(header);
    if (header.size() >= 8 && littleEndian32(bytes) == 20000630u) return exrSize(header);
    if (header.size() >= 24 && std::memcmp(bytes, "\x89PNG\r\n\x1a\n", 8) == 0 &&
        std::memcmp(bytes + 12, "IHDR", 4) == 0)
        return ImageHeaderSize{bigEndian32(bytes + 16), bigEndian32(bytes + 20), false};
    return std::nullopt;
}

std::optional<std::uint64_t> imageHeaderPixels(const std::filesystem::path& file) {
    const std::optional<ImageHeaderSize> size = imageHeaderSize(file);
    if (!size) return std::nullopt;
    return size->width * size->height;
}

} // namespace ibl
