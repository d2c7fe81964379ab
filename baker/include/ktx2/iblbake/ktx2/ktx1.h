// KTX 1.1 cube maps as Filament reads them (docs/formats.md "Filament KTX1"): the one KTX1 product iblbake
// writes, R11G11B10F texels for Filament's Ktx1Reader (cmgen --deploy's <name>_ibl.ktx and
// <name>_skybox.ktx). No Debian package writes KTX1 (libktx is not packaged), and the format is a 64-byte
// header, key/value pairs and the images, so the writer is this file's.
#pragma once

#include "iblbake/core/image.h"

#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace ibl {

// The header's GL enums (Khronos KTX 1.1 file format; OpenGL ES 3.0 tables). glType is GL_R11F_G11F_B10F,
// not the GL_UNSIGNED_INT_10F_11F_11F_REV the KTX text names, because Filament's Ktx1Reader (toPixelDataType)
// maps only the former to its packed type; its loaders refuse the latter.
inline constexpr std::uint32_t kKtx1R11fG11fB10f = 0x8C3A;
inline constexpr std::uint32_t kKtx1Rgb = 0x1907;
// The largest finite values R11G11B10F holds, per channel: (2 - 2^-6) 2^15 for the 11-bit R and G,
// (2 - 2^-5) 2^15 for the 10-bit B (OpenGL ES 3.0, 2.1.3 and 2.1.4).
inline constexpr float kR11G11B10fLargest[3] = {65024.0f, 65024.0f, 64512.0f};

// Every level's six faces (+X, -X, +Y, -Y, +Z, -Z, first row t = 0), levels[0] the largest, each level half
// the previous one's size; `keyValues` in key order. The texels' RGB are packed as R11G11B10F (R bits 0..10,
// G 11..21, B 22..31, rounded to nearest); alpha is dropped.
struct Ktx1Cube {
    std::vector<std::vector<ImageRGBA>> levels;
    std::map<std::string, std::string> keyValues;
};

// The file's bytes. A texel the format cannot hold (a negative, non-finite or larger value than R11G11B10F's
// largest: 65,024 for R and G, 64,512 for B) throws ibl::SettingError("storage", "level <m> face <f> texel
// (<x>, <y>) holds <value>, outside R11G11B10F's 0..<max>"), before anything is written.
std::string encodeKtx1R11G11B10fCube(const Ktx1Cube& cube);

} // namespace ibl
