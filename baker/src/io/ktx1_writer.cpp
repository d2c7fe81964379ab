// The KTX1 cube writer (iblbake/ktx2/ktx1.h).
#include "iblbake/ktx2/ktx1.h"

#include "iblbake/core/error.h"
#include "small_float.h"

#include <cmath>
#include <cstring>

namespace ibl {

namespace {

// The file's identifier and the endianness word a reader of the writer's byte order finds as 0x04030201.
constexpr unsigned char kIdentifier[12] = {0xAB, 0x4B, 0x54, 0x58, 0x20, 0x31,
                                           0x31, 0xBB, 0x0D, 0x0A, 0x1A, 0x0A};
constexpr std::uint32_t kEndianness = 0x04030201;

void appendU32(std::string& out, std::uint32_t value) {
    const unsigned char bytes[4] = {static_cast<unsigned char>(value), static_cast<unsigned char>(value >> 8),
                                    static_cast<unsigned char>(value >> 16),
                                    static_cast<unsigned char>(value >> 24)};
    out.append(reinterpret_cast<const char*>(bytes), 4);
}

// A value R11G11B10F holds: finite and in [0, its channel's largest].
void checkRange(float value, float largest, int level, int face, int x, int y) {
    if (std::isfinite(value) && value >= 0.0f && value <= largest) return;
    throw SettingError("storage", "level " + std::to_string(level) + " face " + std::to_string(face) +
                                      " texel (" + std::to_string(x) + ", " + std::to_string(y) + ") holds " +
                                      std::to_string(value) + ", outside R11G11B10F's 0.." +
                                      std::to_string(int(largest)));
}

} // namespace

std::string encodeKtx1R11G11B10fCube(const Ktx1Cube& cube) {
    if (cube.levels.empty()) throw Error("a KTX1 cube needs at least one level");
    const int baseSize = cube.levels.front().empty() ? 0 : cube.levels.front().front().width;
    for (std::size_t m = 0; m < cube.levels.size(); ++m) {
        const int size = std::max(1, baseSize >> m);
        if (cube.levels[m].size() != 6) throw Error("level " + std::to_string(m) + " has not 6 faces");
        for (const ImageRGBA& face : cube.levels[m])
            if (face.width != size || face.height != size)
                throw Error("level " + std::to_string(m) + " has a face that is not " + std::to_string(size) +
                            " x " + std::to_string(size));
    }

    std::string keyValueData;
    for (const auto& [key, value] : cube.keyValues) {
        const std::uint32_t keyAndValueBytes = std::uint32_t(key.size() + 1 + value.size());
        appendU32(keyValueData, keyAndValueBytes);
        keyValueData += key;
        keyValueData.push_back('\0');
        keyValueData += value;
        keyValueData.append(3 - (keyAndValueBytes + 3) % 4, '\0'); // valuePadding to 4 bytes
    }

    std::string out(reinterpret_cast<const char*>(kIdentifier), sizeof kIdentifier);
    appendU32(out, kEndianness);
    appendU32(out, kKtx1R11fG11fB10f); // glType: see ktx1.h
    appendU32(out, 4);                 // glTypeSize: one packed 32-bit word per texel
    appendU32(out, kKtx1Rgb);          // glFormat
    appendU32(out, kKtx1R11fG11fB10f); // glInternalFormat
    appendU32(out, kKtx1Rgb);          // glBaseInternalFormat
    appendU32(out, std::uint32_t(baseSize));
    appendU32(out, std::uint32_t(baseSize));
    appendU32(out, 0); // pixelDepth
    appendU32(out, 0); // numberOfArrayElements: not an array
    appendU32(out, 6); // numberOfFaces
    appendU32(out, std::uint32_t(cube.levels.size()));
    appendU32(out, std::uint32_t(keyValueData.size()));
    out += keyValueData;

    static_assert(kR11G11B10fLargest[0] == smallfloat::kFloat11Max &&
                  kR11G11B10fLargest[2] == smallfloat::kFloat10Max);
    for (std::size_t m = 0; m < cube.levels.size(); ++m) {
        const int size = cube.levels[m].front().width;
        // For a cube that is not an array, imageSize is the bytes of one face (KTX 1.1, "imageSize"); rows of
        // 4-byte texels need no padding, nor do the faces.
        appendU32(out, std::uint32_t(size) * std::uint32_t(size) * 4u);
        for (int f = 0; f < 6; ++f) {
            const ImageRGBA& face = cube.levels[m][std::size_t(f)];
            for (int y = 0; y < size; ++y)
                for (int x = 0; x < size; ++x) {
                    const glm::vec4& texel = face.at(x, y);
                    for (int c = 0; c < 3; ++c)
                        checkRange(texel[c], kR11G11B10fLargest[c], int(m), f, x, y);
                    appendU32(out, smallfloat::packB10G11R11(texel.r, texel.g, texel.b));
                }
        }
    }
    return out;
}

} // namespace ibl
