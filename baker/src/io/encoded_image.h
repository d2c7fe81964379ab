// Images encoded in memory by OpenImageIO and written by writeFileBytes (atomic_file.h), so that a full
// disk or a read-only directory is reported with the system's reason and the target's name (the format
// libraries' own messages name the temporary file and not the cause).
#pragma once

#include <OpenImageIO/imageio.h>

#include <cstddef>
#include <filesystem>

namespace ibl {

// Writes `pixels` (of `type`, `stride` bytes from one pixel to the next, or AutoStride) as the format
// `format` ("exr", "png") with `spec` to `path` through a temporary file. Throws ibl::OutputError naming
// `path`.
void writeEncodedImage(const std::filesystem::path& path, const char* format, OIIO::ImageSpec spec,
                       OIIO::TypeDesc type, const void* pixels, OIIO::stride_t stride = OIIO::AutoStride);

} // namespace ibl
