// KTX 2.0 container output and input for cube-map chains, 2D LUTs and 2D arrays (light cards) (float formats
// and BC6H, no supercompression). Layout follows the KTX 2.0 specification (Khronos); the Data
// Format Descriptor follows the Khronos Data Format Specification's basic descriptor block for each vkFormat.
#pragma once

#include "iblbake/core/cubemap.h"
#include "iblbake/core/image.h"

#include <cstdint>
#include <filesystem>
#include <map>
#include <span>
#include <string>
#include <utility>
#include <vector>

namespace ibl {

// VK_FORMAT_R16G16B16A16_SFLOAT (97), VK_FORMAT_R32G32B32A32_SFLOAT (109),
// VK_FORMAT_B10G11R11_UFLOAT_PACK32 (122), VK_FORMAT_E5B9G9R9_UFLOAT_PACK32 (123), and
// VK_FORMAT_BC6H_UFLOAT_BLOCK (131) made by our encoder at its default, fast or best preset (one GPU format,
// three efforts; docs/formats.md "BC6H").
enum class Ktx2Format { RGBA16F, RGBA32F, B10G11R11, E5B9G9R9, BC6H, BC6HFast, BC6HBest };

inline bool isBc6h(Ktx2Format format) {
    return format == Ktx2Format::BC6H || format == Ktx2Format::BC6HFast || format == Ktx2Format::BC6HBest;
}

// The names of the formats (`--format`, the scene's outputs.ktx2Format), in Ktx2Format order.
inline const std::vector<std::string> kKtx2FormatNames = {"rgba16f", "rgba32f",   "b10g11r11", "e5b9g9r9",
                                                          "bc6h",    "bc6h-fast", "bc6h-best"};
// Throws ibl::Error "'<name>' is not one of rgba16f, rgba32f, ..." for any other name.
Ktx2Format parseKtx2Format(const std::string& name);

// What the writer had to change to make the data storable. Each texel counts at most once per field.
struct Ktx2WriteStats {
    std::uint64_t clampedTexels = 0;     // a finite channel outside the format's range (|v| > max, or v < 0
                                         // for the unsigned packed formats) was clamped to it
    std::uint64_t repairedNonFinite = 0; // a channel was NaN (-> 0) or +-Inf (-> the range limit)
    std::uint64_t fileBytes = 0;         // the file as written
    std::uint64_t gpuBytes = 0;          // its texels as a GPU holds them: every level's images
    double encodeSeconds = 0.0;          // time spent encoding texels (BC6H: the block encoder)
};

using Ktx2KeyValues = std::vector<std::pair<std::string, std::string>>;

// How RGB relates to A, written as the DFD's KHR_DF_FLAG_ALPHA_PREMULTIPLIED (KDF 5.6 "flags"): a local
// probe's LD holds colour x visibility (Premultiplied); everything else stores alpha 1 or no alpha.
enum class Ktx2Alpha { Straight, Premultiplied };

// Writes a cube map with every level of `chain` (levels[0] largest, level m of face size max(1, base >> m)).
// Key/value pairs are written sorted by key, each value NUL-terminated, together with
// "KTXwriter" = "iblbake <version>" (the caller may not pass that key, nor an empty or duplicate key).
// The file is written to a temporary name and renamed when complete (ibl::AtomicFile). Throws ibl::Error
// "<file>: <problem>" on invalid input or any I/O failure; an existing file at `path` is then untouched.
// BC6H stores unsigned finite halves: a negative or non-finite channel is such a problem (checked before
// any block is encoded), levels below 4 x 4 are one block an image (docs/formats.md "BC6H").
Ktx2WriteStats writeKtx2Cube(const std::filesystem::path& path, const CubeMapChain& chain, Ktx2Format format,
                             const Ktx2KeyValues& keyValues, Ktx2Alpha alpha = Ktx2Alpha::Straight);

// Writes a cube map array (faceCount 6, layerCount = layers.size() >= 1, levelCount 1), every layer with the
// same face size, e.g. the rough layers (kernels/mip_mapping.h). Same conventions as writeKtx2Cube,
// including the mirrored storage of iblbake.profile "three".
Ktx2WriteStats writeKtx2CubeArray(const std::filesystem::path& path, const std::vector<CubeMap>& layers,
                                  Ktx2Format format, const Ktx2KeyValues& keyValues);

// Writes one 2D image (faceCount 1, levelCount 1), e.g. a LUT. Same conventions as writeKtx2Cube.
Ktx2WriteStats writeKtx2Image(const std::filesystem::path& path, const ImageRGBA& image, Ktx2Format format,
                              const Ktx2KeyValues& keyValues);

// Writes a 2D array texture (faceCount 1, layerCount = levels[0].size() >= 1): levels[m][layer], level m of
// size max(1, width >> m) x max(1, height >> m), every level with the same layers. Same conventions as
// writeKtx2Cube.
Ktx2WriteStats writeKtx2Array(const std::filesystem::path& path,
                              const std::vector<std::vector<ImageRGBA>>& levels, Ktx2Format format,
                              const Ktx2KeyValues& keyValues);

struct Ktx2Image {
    std::uint32_t vkFormat = 0;
    std::uint32_t pixelWidth = 0;
    std::uint32_t pixelHeight = 0;
    std::uint32_t faceCount = 0;
    std::uint32_t layerCount = 0;                 // 0: not an array; else 2D (faceCount 1) or cube (6) arrays
    std::uint32_t levelCount = 0;                 // as stored in the header; 0 means "base level only"
    std::map<std::string, std::string> keyValues; // one trailing NUL of each value removed
    Ktx2Alpha alpha = Ktx2Alpha::Straight;        // the DFD's premultiplied-alpha flag
    // levels[m][face], or levels[m][layer * faceCount + face] for an array, max(1, levelCount) levels,
    // decoded to float RGBA (alpha 1 for formats without alpha). Values are decoded as stored: a foreign file
    // may contain Inf/NaN texels.
    std::vector<std::vector<ImageRGBA>> levels;
};

// Reads a file written by writeKtx2Cube/writeKtx2Image or any conforming writer using one of the formats
// above (BC6H decoded by our decoder, bc6h.h). Every structural field is validated against the specification
// and the file size before use; damage of any kind gives ibl::Error "<file>: <problem>".
Ktx2Image readKtx2(const std::filesystem::path& path);

// The same for a file's bytes already in memory; `name` stands for the file in error messages.
Ktx2Image parseKtx2(std::span<const std::uint8_t> bytes, const std::string& name);

} // namespace ibl
