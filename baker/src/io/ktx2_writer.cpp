// KTX 2.0 writer: header, Index, Level Index, DFD and key/value data (KTX 2.0 "File Structure"), then the
// mip levels from the smallest to the largest, each aligned to lcm(texel block size, 4). Texels are
// sanitized (NaN, Inf, out-of-range values) and counted before encoding, so no Inf/NaN is ever stored.
#include "iblbake/core/error.h"
#include "iblbake/ktx2/atomic_file.h"
#include "iblbake/ktx2/cube_profile.h"
#include "iblbake/ktx2/ktx2.h"
#include "ktx2_format.h"
#include "small_float.h"

#include <glm/vec3.hpp>

#include <algorithm>
#include <bit>
#include <cerrno>
#include <cfloat>
#include <chrono>
#include <cmath>
#include <cstring>
#include <fcntl.h>
#include <unistd.h>

namespace ibl {

namespace {

namespace fs = std::filesystem;
using ktx2::FormatInfo;

class ByteSink {
  public:
    void u32(std::uint32_t v) {
        for (int i = 0; i < 4; ++i)
            bytes.push_back(std::uint8_t(v >> (8 * i)));
    }
    void u64(std::uint64_t v) {
        for (int i = 0; i < 8; ++i)
            bytes.push_back(std::uint8_t(v >> (8 * i)));
    }
    void text(const std::string& s) { bytes.insert(bytes.end(), s.begin(), s.end()); }
    void zeros(std::size_t n) { bytes.insert(bytes.end(), n, std::uint8_t(0)); }
    std::vector<std::uint8_t> bytes;
};

std::uint64_t alignUp(std::uint64_t v, std::uint64_t a) {
    return (v + a - 1) / a * a;
}

// One level as the writer sees it: its size and its images, in KTX2's order within a level (layer by
// layer, face by face within a layer).
struct LevelView {
    int width = 0;
    int height = 0;
    std::vector<const ImageRGBA*> faces;
};

// A POSIX file that reports every failure (short writes, EFBIG, ENOSPC, fsync) as ibl::Error.
class OutputFile {
  public:
    OutputFile(const fs::path& temp, std::string name) : name_(std::move(name)) {
        fd_ = ::open(temp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
        if (fd_ < 0) fail("cannot create a temporary file");
    }
    ~OutputFile() {
        if (fd_ >= 0) ::close(fd_);
    }
    OutputFile(const OutputFile&) = delete;
    OutputFile& operator=(const OutputFile&) = delete;

    void write(const std::vector<std::uint8_t>& data) {
        const std::uint8_t* p = data.data();
        std::size_t left = data.size();
        while (left > 0) {
            const ssize_t n = ::write(fd_, p, left);
            if (n < 0 && errno == EINTR) continue;
            if (n <= 0) fail("cannot write");
            p += n;
            left -= std::size_t(n);
        }
        written_ += data.size();
    }
    std::uint64_t written() const { return written_; }
    // fsync before the rename, so a crash cannot leave a renamed but empty file.
    void close() {
        if (::fsync(fd_) != 0) fail("cannot flush to disk");
        const int fd = fd_;
        fd_ = -1;
        if (::close(fd) != 0) fail("cannot close");
    }

  private:
    [[noreturn]] void fail(const char* what) {
        throw OutputError(name_ + ": " + what + ": " + std::strerror(errno));
    }
    std::string name_;
    int fd_ = -1;
    std::uint64_t written_ = 0;
};

// Texel sanitizer: returns the channel value to store and records what had to change.
struct TexelFlags {
    bool clamped = false;
    bool nonFinite = false;
};

float sanitize(float v, float lo, float hi, TexelFlags& flags) {
    if (std::isnan(v)) {
        flags.nonFinite = true;
        return 0.0f;
    }
    if (std::isinf(v)) {
        flags.nonFinite = true;
        return v > 0 ? hi : lo;
    }
    if (v > hi) {
        flags.clamped = true;
        return hi;
    }
    if (v < lo) {
        flags.clamped = true;
        return lo;
    }
    return v;
}

// The RGB of a packed unsigned format: each channel sanitized to [0, its largest value].
glm::vec3 sanitizeRgb(const glm::vec4& texel, const glm::vec3& largest, TexelFlags& flags) {
    return {sanitize(texel.r, 0.0f, largest.r, flags), sanitize(texel.g, 0.0f, largest.g, flags),
            sanitize(texel.b, 0.0f, largest.b, flags)};
}

// Little-endian stores at `out`.
void storeU16(std::uint8_t* out, std::uint16_t v) {
    out[0] = std::uint8_t(v);
    out[1] = std::uint8_t(v >> 8);
}
void storeU32(std::uint8_t* out, std::uint32_t v) {
    for (int i = 0; i < 4; ++i)
        out[i] = std::uint8_t(v >> (8 * i));
}

// Writes one texel's texelBytes at `out`. Straight into the level's bytes, not byte by byte into a growing
// vector (with small_float.h's rounding, the 1k sample's chain in 26 -> 11 ms).
void encodeTexel(const glm::vec4& texel, Ktx2Format format, std::uint8_t* out, Ktx2WriteStats& stats) {
    TexelFlags flags;
    switch (format) {
    case Ktx2Format::BC6H: // block formats: encodeBc6hImage
    case Ktx2Format::BC6HFast:
    case Ktx2Format::BC6HBest:
        return;
    case Ktx2Format::RGBA16F:
        for (int c = 0; c < 4; ++c)
            storeU16(out + 2 * c, smallfloat::floatToHalf(sanitize(texel[c], -smallfloat::kHalfMax,
                                                                   smallfloat::kHalfMax, flags)));
        break;
    case Ktx2Format::RGBA32F:
        for (int c = 0; c < 4; ++c)
            storeU32(out + 4 * c, ktx2::floatBits(sanitize(texel[c], -FLT_MAX, FLT_MAX, flags)));
        break;
    case Ktx2Format::B10G11R11: {
        const glm::vec3 rgb = sanitizeRgb(
            texel, {smallfloat::kFloat11Max, smallfloat::kFloat11Max, smallfloat::kFloat10Max}, flags);
        storeU32(out, smallfloat::packB10G11R11(rgb.r, rgb.g, rgb.b));
        break;
    }
    case Ktx2Format::E5B9G9R9: {
        const glm::vec3 rgb = sanitizeRgb(texel, glm::vec3(smallfloat::kRgb9e5Max), flags);
        storeU32(out, smallfloat::packE5B9G9R9(rgb.r, rgb.g, rgb.b));
        break;
    }
    }
    stats.clampedTexels += flags.clamped ? 1 : 0;
    stats.repairedNonFinite += flags.nonFinite ? 1 : 0;
}

// BC6H stores unsigned finite halves: a negative or non-finite channel is refused (nothing is written),
// one above 65,504 is clamped and counted like the other formats' (the storage scale keeps a product
// below it). Checked over every image before the first block is encoded.
void checkBc6hTexels(const std::string& name, const std::vector<LevelView>& levels) {
    for (std::size_t m = 0; m < levels.size(); ++m)
        for (std::size_t f = 0; f < levels[m].faces.size(); ++f) {
            const ImageRGBA& image = *levels[m].faces[f];
            for (std::size_t i = 0; i < image.pixels.size(); ++i)
                for (int c = 0; c < 3; ++c) {
                    const float v = image.pixels[i][c];
                    if (std::isfinite(v) && v >= 0.0f) continue;
                    throw Error(name + ": bc6h stores no negative or non-finite value; level " +
                                std::to_string(m) + " image " + std::to_string(f) + " texel (" +
                                std::to_string(i % std::size_t(image.width)) + ", " +
                                std::to_string(i / std::size_t(image.width)) + ") channel " + "RGB"[c] +
                                " holds " + std::to_string(v));
                }
        }
}

// One image's BC6H blocks at `out`, its channels above the half range clamped and counted.
void encodeBc6hImage(const ImageRGBA& image, bc6h::Preset preset, std::uint8_t* out, Ktx2WriteStats& stats) {
    ImageRGBA clamped = image;
    for (glm::vec4& texel : clamped.pixels) {
        TexelFlags flags;
        for (int c = 0; c < 3; ++c)
            texel[c] = sanitize(texel[c], 0.0f, smallfloat::kHalfMax, flags);
        stats.clampedTexels += flags.clamped ? 1 : 0;
    }
    bc6h::encodeImage(clamped, preset, out);
}

// One image's bytes at `out`: ktx2::imageBytes(info, width, height) of them.
void encodeImage(const ImageRGBA& image, const ktx2::FormatInfo& info, std::uint8_t* out,
                 Ktx2WriteStats& stats) {
    if (info.blockSize > 1) {
        encodeBc6hImage(image, info.preset, out, stats);
        return;
    }
    for (const glm::vec4& texel : image.pixels) {
        encodeTexel(texel, info.format, out, stats);
        out += info.texelBytes;
    }
}

// KTX 2.0 "Key/Value Data": pairs sorted by the code points of the keys (byte order of UTF-8, which is
// what std::string's comparison gives), each keyAndValueByteLength followed by key, NUL, value, NUL and
// valuePadding to a multiple of 4. kvdByteLength includes all padding.
std::vector<std::uint8_t> keyValueData(const std::string& name, const Ktx2KeyValues& callerPairs) {
    Ktx2KeyValues pairs = callerPairs;
    for (const auto& [key, value] : pairs) {
        if (key.empty()) throw Error(name + ": empty metadata key");
        if (key.find('\0') != std::string::npos) throw Error(name + ": metadata key contains a NUL byte");
        if (key == "KTXwriter") throw Error(name + ": metadata key KTXwriter is reserved for the writer");
    }
    pairs.emplace_back("KTXwriter", std::string("iblbake ") + IBLBAKE_VERSION);
    std::sort(pairs.begin(), pairs.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    for (std::size_t i = 1; i < pairs.size(); ++i)
        if (pairs[i].first == pairs[i - 1].first)
            throw Error(name + ": duplicate metadata key " + pairs[i].first);

    ByteSink kvd;
    for (const auto& [key, value] : pairs) {
        const std::size_t length = key.size() + 1 + value.size() + 1;
        if (length > 0xFFFFFFFFu) throw Error(name + ": metadata value for " + key + " is too large");
        kvd.u32(std::uint32_t(length));
        kvd.text(key);
        kvd.zeros(1);
        kvd.text(value);
        kvd.zeros(1);
        kvd.zeros(alignUp(length, 4) - length);
    }
    return std::move(kvd.bytes);
}

// layerCount 0: not an array (each level's images are its faces); else an array of that many layers of
// faceCount faces (1: 2D, 6: cube), each level's images layer by layer, face by face within a layer.
Ktx2WriteStats writeKtx2(const fs::path& path, const std::vector<LevelView>& levels, Ktx2Format format,
                         const Ktx2KeyValues& keyValues, std::uint32_t layerCount = 0,
                         Ktx2Alpha alpha = Ktx2Alpha::Straight, std::uint32_t arrayFaceCount = 1) {
    const std::string name = path.string();
    const FormatInfo& info = ktx2::formatInfo(format);
    const std::uint32_t imagesPerLevel = std::uint32_t(levels.front().faces.size());
    const std::uint32_t faceCount = layerCount == 0 ? imagesPerLevel : arrayFaceCount;
    const std::uint32_t levelCount = std::uint32_t(levels.size());

    const std::vector<std::uint32_t> dfd = ktx2::dataFormatDescriptor(format, alpha);
    const std::vector<std::uint8_t> kvd = keyValueData(name, keyValues);

    // Section offsets: header and Index, Level Index, DFD, KVD, then (no supercompression global data)
    // the levels, smallest first, each after its mipPadding.
    const std::uint64_t dfdOffset = ktx2::kHeaderBytes + ktx2::kLevelIndexEntryBytes * levelCount;
    const std::uint64_t dfdBytes = 4 * dfd.size();
    const std::uint64_t kvdOffset = dfdOffset + dfdBytes;
    const std::uint64_t alignment = ktx2::levelAlignment(info);
    std::vector<std::uint64_t> levelOffset(levelCount), levelBytes(levelCount);
    std::uint64_t cursor = kvdOffset + kvd.size();
    if (cursor > 0xFFFFFFFFu) throw Error(name + ": metadata too large for the 32-bit KTX2 index");
    if (info.blockSize > 1) checkBc6hTexels(name, levels);
    for (std::uint32_t p = levelCount; p-- > 0;) {
        levelBytes[p] = std::uint64_t(imagesPerLevel) * ktx2::imageBytes(info, std::uint64_t(levels[p].width),
                                                                         std::uint64_t(levels[p].height));
        levelOffset[p] = alignUp(cursor, alignment);
        cursor = levelOffset[p] + levelBytes[p];
    }

    ByteSink head;
    head.bytes.assign(ktx2::kIdentifier.begin(), ktx2::kIdentifier.end());
    head.u32(info.vkFormat);
    head.u32(info.typeSize);
    head.u32(std::uint32_t(levels.front().width));
    head.u32(std::uint32_t(levels.front().height));
    head.u32(0); // pixelDepth: not a 3D texture
    head.u32(layerCount);
    head.u32(faceCount);
    head.u32(levelCount);
    head.u32(0); // supercompressionScheme: none
    head.u32(std::uint32_t(dfdOffset));
    head.u32(std::uint32_t(dfdBytes));
    head.u32(std::uint32_t(kvdOffset));
    head.u32(std::uint32_t(kvd.size()));
    head.u64(0); // sgdByteOffset
    head.u64(0); // sgdByteLength
    for (std::uint32_t p = 0; p < levelCount; ++p) {
        head.u64(levelOffset[p]);
        head.u64(levelBytes[p]);
        head.u64(levelBytes[p]); // uncompressedByteLength equals byteLength without supercompression
    }
    for (std::uint32_t w : dfd)
        head.u32(w);
    head.bytes.insert(head.bytes.end(), kvd.begin(), kvd.end());

    AtomicFile atomic(path);
    OutputFile out(atomic.tempPath(), name);
    out.write(head.bytes);
    Ktx2WriteStats stats;
    for (std::uint32_t p = levelCount; p-- > 0;) {
        const std::uint64_t padding = levelOffset[p] - out.written(); // mipPadding, zeros
        std::vector<std::uint8_t> level(padding + levelBytes[p]);
        std::uint8_t* texelBytes = level.data() + padding;
        const auto start = std::chrono::steady_clock::now();
        for (const ImageRGBA* face : levels[p].faces) {
            encodeImage(*face, info, texelBytes, stats);
            texelBytes += ktx2::imageBytes(info, std::uint64_t(face->width), std::uint64_t(face->height));
        }
        stats.encodeSeconds +=
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        stats.gpuBytes += levelBytes[p];
        out.write(level);
    }
    stats.fileBytes = out.written();
    out.close();
    atomic.commit();
    return stats;
}

void checkImage(const std::string& name, const ImageRGBA& image, int width, int height,
                const std::string& what) {
    if (image.width != width || image.height != height ||
        image.pixels.size() != std::size_t(width) * std::size_t(height))
        throw Error(name + ": " + what + " is " + std::to_string(image.width) + "x" +
                    std::to_string(image.height) + " with " + std::to_string(image.pixels.size()) +
                    " pixels, expected " + std::to_string(width) + "x" + std::to_string(height));
}

// The cubes in the layout the file's iblbake.profile declares (cube_profile.h): `cubes` itself, or for
// three.js's layout their copy in `mirrored`, each mirrored in x.
const std::vector<CubeMap>& inProfileLayout(const std::string& name, const std::vector<CubeMap>& cubes,
                                            const Ktx2KeyValues& keyValues, std::vector<CubeMap>& mirrored) {
    const auto profile = std::find_if(keyValues.begin(), keyValues.end(),
                                      [](const auto& kv) { return kv.first == kCubeProfileKey; });
    try {
        if (profile == keyValues.end() || parseCubeProfile(profile->second) != CubeProfile::Three)
            return cubes;
    } catch (const Error& e) {
        throw Error(name + ": " + kCubeProfileKey + ": " + e.what());
    }
    mirrored = cubes;
    for (CubeMap& cube : mirrored)
        mirrorCubeFacesX(cube.faces);
    return mirrored;
}

} // namespace

Ktx2WriteStats writeKtx2Cube(const fs::path& path, const CubeMapChain& chain, Ktx2Format format,
                             const Ktx2KeyValues& keyValues, Ktx2Alpha alpha) {
    const std::string name = path.string();
    if (chain.levels.empty()) throw Error(name + ": refusing to write a cube map without levels");
    const int base = chain.levels.front().faceSize;
    if (base <= 0) throw Error(name + ": refusing to write a cube map of face size " + std::to_string(base));
    // KTX 2.0 "levelCount": at most floor(log2(size)) + 1 levels.
    const std::size_t maxLevels = std::size_t(std::bit_width(unsigned(base)));
    if (chain.levels.size() > maxLevels)
        throw Error(name + ": " + std::to_string(chain.levels.size()) + " levels for face size " +
                    std::to_string(base) + " (at most " + std::to_string(maxLevels) + ")");

    std::vector<CubeMap> mirrored;
    const std::vector<CubeMap>& stored = inProfileLayout(name, chain.levels, keyValues, mirrored);

    std::vector<LevelView> levels;
    for (std::size_t m = 0; m < stored.size(); ++m) {
        const CubeMap& level = stored[m];
        const int size = std::max(1, base >> m);
        if (level.faceSize != size)
            throw Error(name + ": level " + std::to_string(m) + " has face size " +
                        std::to_string(level.faceSize) + ", expected " + std::to_string(size));
        LevelView view{size, size, {}};
        for (std::size_t f = 0; f < level.faces.size(); ++f) {
            checkImage(name, level.faces[f], size, size,
                       "level " + std::to_string(m) + " face " + std::to_string(f));
            view.faces.push_back(&level.faces[f]);
        }
        levels.push_back(std::move(view));
    }
    return writeKtx2(path, levels, format, keyValues, 0, alpha);
}

Ktx2WriteStats writeKtx2Array(const fs::path& path, const std::vector<std::vector<ImageRGBA>>& levels,
                              Ktx2Format format, const Ktx2KeyValues& keyValues) {
    const std::string name = path.string();
    if (levels.empty() || levels.front().empty())
        throw Error(name + ": refusing to write an array without levels or layers");
    const int width = levels.front().front().width, height = levels.front().front().height;
    if (width <= 0 || height <= 0) throw Error(name + ": refusing to write an empty array");
    const std::size_t maxLevels = std::size_t(std::bit_width(unsigned(std::max(width, height))));
    if (levels.size() > maxLevels)
        throw Error(name + ": " + std::to_string(levels.size()) + " levels for size " +
                    std::to_string(width) + "x" + std::to_string(height) + " (at most " +
                    std::to_string(maxLevels) + ")");
    const std::size_t layers = levels.front().size();
    std::vector<LevelView> views;
    for (std::size_t m = 0; m < levels.size(); ++m) {
        const int w = std::max(1, width >> m), h = std::max(1, height >> m);
        if (levels[m].size() != layers)
            throw Error(name + ": level " + std::to_string(m) + " has " + std::to_string(levels[m].size()) +
                        " layers, expected " + std::to_string(layers));
        LevelView view{w, h, {}};
        for (std::size_t l = 0; l < layers; ++l) {
            checkImage(name, levels[m][l], w, h,
                       "level " + std::to_string(m) + " layer " + std::to_string(l));
            view.faces.push_back(&levels[m][l]);
        }
        views.push_back(std::move(view));
    }
    return writeKtx2(path, views, format, keyValues, std::uint32_t(layers));
}

Ktx2WriteStats writeKtx2CubeArray(const fs::path& path, const std::vector<CubeMap>& layers, Ktx2Format format,
                                  const Ktx2KeyValues& keyValues) {
    const std::string name = path.string();
    if (layers.empty()) throw Error(name + ": refusing to write a cube map array without layers");
    const int size = layers.front().faceSize;
    if (size <= 0)
        throw Error(name + ": refusing to write a cube map array of face size " + std::to_string(size));
    std::vector<CubeMap> mirrored;
    const std::vector<CubeMap>& stored = inProfileLayout(name, layers, keyValues, mirrored);
    LevelView view{size, size, {}};
    for (std::size_t l = 0; l < stored.size(); ++l)
        for (std::size_t f = 0; f < stored[l].faces.size(); ++f) {
            checkImage(name, stored[l].faces[f], size, size,
                       "layer " + std::to_string(l) + " face " + std::to_string(f));
            view.faces.push_back(&stored[l].faces[f]);
        }
    return writeKtx2(path, {view}, format, keyValues, std::uint32_t(stored.size()), Ktx2Alpha::Straight, 6);
}

Ktx2WriteStats writeKtx2Image(const fs::path& path, const ImageRGBA& image, Ktx2Format format,
                              const Ktx2KeyValues& keyValues) {
    const std::string name = path.string();
    if (image.width <= 0 || image.height <= 0) throw Error(name + ": refusing to write an empty image");
    checkImage(name, image, image.width, image.height, "the image");
    return writeKtx2(path, {LevelView{image.width, image.height, {&image}}}, format, keyValues);
}

} // namespace ibl
