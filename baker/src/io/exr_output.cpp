#include "iblbake/baker/exr_output.h"
#include "encoded_image.h"
#include "iblbake/core/error.h"

#include <OpenImageIO/imageio.h>

#include <algorithm>

namespace ibl {

void writeExr(const std::filesystem::path& path, const ImageRGBA& image, const ExrOutputOptions& options) {
    if (image.width <= 0 || image.height <= 0)
        throw Error(path.string() + ": refusing to write an empty image");
    const int channels = std::clamp(options.channels, 1, 4);
    OIIO::ImageSpec spec(image.width, image.height, channels,
                         options.pixelType == PixelType::Half ? OIIO::TypeDesc::HALF : OIIO::TypeDesc::FLOAT);
    spec.attribute("compression", "zip");
    for (const auto& [key, value] : options.attributes)
        spec.attribute(key, value);
    // The in-memory image is RGBA; a stride of 4 floats selects the first `channels` of each pixel.
    writeEncodedImage(path, "exr", spec, OIIO::TypeDesc::FLOAT, image.pixels.data(), sizeof(glm::vec4));
}

} // namespace ibl
