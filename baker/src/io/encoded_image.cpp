#include "encoded_image.h"

#include "iblbake/core/error.h"
#include "iblbake/ktx2/atomic_file.h"

#include <png.h>

namespace ibl {

void writeEncodedImage(const std::filesystem::path& path, std::string_view bytes) {
    AtomicFile file(path);
    writeFileBytes(file.tempPath(), bytes, path.string());
    file.commit();
}

std::vector<std::uint8_t> encodePng(const std::filesystem::path& path, int width, int height, int channels,
                                    const std::uint8_t* pixels) {
    // libpng's simplified API: 8-bit colour is written as given (alpha straight, no gamma conversion).
    png_image image{};
    image.version = PNG_IMAGE_VERSION;
    image.width = png_uint_32(width);
    image.height = png_uint_32(height);
    image.format = channels == 4 ? PNG_FORMAT_RGBA : PNG_FORMAT_RGB;
    png_alloc_size_t size = 0;
    const png_int_32 rowStride = png_int_32(width * channels);
    if (!png_image_write_get_memory_size(image, size, 0, pixels, rowStride, nullptr))
        throw OutputError(path.string() + ": cannot encode the PNG: " + image.message);
    std::vector<std::uint8_t> encoded(size);
    if (!png_image_write_to_memory(&image, encoded.data(), &size, 0, pixels, rowStride, nullptr))
        throw OutputError(path.string() + ": cannot encode the PNG: " + image.message);
    encoded.resize(size);
    return encoded;
}

} // namespace ibl
