// Images encoded in memory and written by writeFileBytes (atomic_file.h), so that a full disk or a
// read-only directory is reported with the system's reason and the target's name (the format libraries'
// own messages name the temporary file and not the cause).
#pragma once

#include <cstdint>
#include <filesystem>
#include <string_view>
#include <vector>

namespace ibl {

// Writes `bytes` (an encoded file) to `path` through a temporary file. Throws ibl::OutputError naming `path`.
void writeEncodedImage(const std::filesystem::path& path, std::string_view bytes);

// 8-bit PNG of `channels` (3: RGB, 4: RGBA with straight alpha) interleaved bytes, rows top to bottom.
// Throws ibl::OutputError naming `path` when libpng cannot encode it.
std::vector<std::uint8_t> encodePng(const std::filesystem::path& path, int width, int height, int channels,
                                    const std::uint8_t* pixels);

} // namespace ibl
