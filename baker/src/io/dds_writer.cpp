// KTX2 to DDS (iblbake/ktx2/dds.h). Field values from the DDS programming guide: DDS_HEADER,
// DDS_PIXELFORMAT, DDS_HEADER_DXT10.
#include "iblbake/ktx2/dds.h"

#include "iblbake/core/error.h"
#include "iblbake/ktx2/atomic_file.h"
#include "iblbake/ktx2/ktx2.h"
#include "ktx2_format.h"

#include <algorithm>
#include <fstream>
#include <iterator>
#include <string>

namespace ibl {

namespace {

constexpr std::uint32_t kMagic = 0x20534444; // "DDS "
constexpr std::uint32_t kHeaderSize = 124, kPixelFormatSize = 32;
constexpr std::uint32_t kDdsdCaps = 0x1, kDdsdHeight = 0x2, kDdsdWidth = 0x4, kDdsdPitch = 0x8,
                        kDdsdPixelFormat = 0x1000, kDdsdMipMapCount = 0x20000, kDdsdLinearSize = 0x80000;
constexpr std::uint32_t kDdpfFourCc = 0x4, kFourCcDx10 = 0x30315844; // "DX10"
constexpr std::uint32_t kCapsComplex = 0x8, kCapsTexture = 0x1000, kCapsMipMap = 0x400000;
constexpr std::uint32_t kCaps2CubeMapAllFaces = 0x200 | 0xFC00; // DDSCAPS2_CUBEMAP and the six face bits
constexpr std::uint32_t kResourceDimensionTexture2d = 3, kMiscTextureCube = 0x4;
constexpr std::uint32_t kAlphaModeUnknown = 0, kAlphaModePremultiplied = 2;

void put(std::vector<std::uint8_t>& bytes, std::uint32_t v) {
    for (int i = 0; i < 4; ++i)
        bytes.push_back(std::uint8_t(v >> (8 * i)));
}

std::uint64_t u64At(std::span<const std::uint8_t> bytes, std::size_t offset) {
    std::uint64_t v = 0;
    for (int i = 0; i < 8; ++i)
        v |= std::uint64_t(bytes[offset + std::size_t(i)]) << (8 * i);
    return v;
}

} // namespace

std::vector<std::uint8_t> ddsFromKtx2(std::span<const std::uint8_t> ktx2, const std::string& name) {
    const Ktx2Image image = parseKtx2(ktx2, name); // every offset and length checked
    const ktx2::FormatInfo info = *ktx2::findFormat(image.vkFormat);
    const bool cube = image.faceCount == 6;
    const bool blocks = info.blockSize > 1;
    const std::uint32_t levelCount = std::max(1u, image.levelCount);
    const std::uint32_t width = image.pixelWidth, height = image.pixelHeight;

    std::vector<std::uint8_t> dds;
    put(dds, kMagic);
    put(dds, kHeaderSize);
    put(dds, kDdsdCaps | kDdsdHeight | kDdsdWidth | kDdsdPixelFormat |
                 (levelCount > 1 ? kDdsdMipMapCount : 0) | (blocks ? kDdsdLinearSize : kDdsdPitch));
    put(dds, height);
    put(dds, width);
    put(dds, blocks ? std::uint32_t(ktx2::imageBytes(info, width, height)) : width * info.texelBytes);
    put(dds, 0); // depth
    put(dds, levelCount);
    for (int i = 0; i < 11; ++i)
        put(dds, 0); // reserved1
    put(dds, kPixelFormatSize);
    put(dds, kDdpfFourCc);
    put(dds, kFourCcDx10);
    for (int i = 0; i < 5; ++i)
        put(dds, 0); // RGBBitCount and the four masks
    put(dds, kCapsTexture | (levelCount > 1 ? kCapsMipMap | kCapsComplex : 0) | (cube ? kCapsComplex : 0));
    put(dds, cube ? kCaps2CubeMapAllFaces : 0);
    for (int i = 0; i < 3; ++i)
        put(dds, 0); // caps3, caps4, reserved2
    put(dds, info.dxgiFormat);
    put(dds, kResourceDimensionTexture2d);
    put(dds, cube ? kMiscTextureCube : 0);
    put(dds, std::max(1u, image.layerCount)); // arraySize: cubes for a cube map, images for a 2D array
    put(dds, image.alpha == Ktx2Alpha::Premultiplied ? kAlphaModePremultiplied : kAlphaModeUnknown);

    // KTX2 holds level by level (each level's images layer by layer, face by face), DDS image by image.
    const std::size_t images = std::size_t(image.faceCount) * std::max(1u, image.layerCount);
    for (std::size_t i = 0; i < images; ++i)
        for (std::uint32_t m = 0; m < levelCount; ++m) {
            const std::uint64_t bytes =
                ktx2::imageBytes(info, std::max(1u, width >> m), std::max(1u, height >> m));
            const std::uint64_t offset =
                u64At(ktx2, ktx2::kHeaderBytes + ktx2::kLevelIndexEntryBytes * m) + i * bytes;
            const auto first = ktx2.begin() + std::ptrdiff_t(offset);
            dds.insert(dds.end(), first, first + std::ptrdiff_t(bytes));
        }
    return dds;
}

void writeDdsFromKtx2(const std::filesystem::path& ktx2File, const std::filesystem::path& target) {
    std::ifstream in(ktx2File, std::ios::binary);
    const std::vector<std::uint8_t> bytes{std::istreambuf_iterator<char>(in),
                                          std::istreambuf_iterator<char>()};
    if (!in.good() && !in.eof()) throw Error(ktx2File.string() + ": cannot read the file");
    const std::vector<std::uint8_t> dds = ddsFromKtx2(bytes, ktx2File.string());
    writeFileBytes(target, std::string_view(reinterpret_cast<const char*>(dds.data()), dds.size()));
}

} // namespace ibl
