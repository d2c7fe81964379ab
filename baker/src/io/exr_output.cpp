#include "iblbake/baker/exr_output.h"
#include "iblbake/core/error.h"
#include "iblbake/ktx2/atomic_file.h"

#include <OpenImageIO/imageio.h>

#include <algorithm>

namespace ibl {

void writeExr(const std::filesystem::path& path, const ImageRGBA& image, const ExrOutputOptions& options) {
    if (image.width <= 0 || image.height <= 0)
        throw Error(path.string() + ": refusing to write an empty image");
    AtomicFile file(path);
    const int channels = std::clamp(options.channels, 1, 4);
    OIIO::ImageSpec spec(image.width, image.height, channels,
                         options.pixelType == PixelType::Half ? OIIO::TypeDesc::HALF : OIIO::TypeDesc::FLOAT);
    spec.attribute("compression", "zip");
    for (const auto& [key, value] : options.attributes)
        spec.attribute(key, value);

    auto out = OIIO::ImageOutput::create(file.tempPath().string());
    if (!out) throw Error(path.string() + ": cannot create an OpenEXR writer: " + OIIO::geterror());
    if (!out->open(file.tempPath().string(), spec)) throw Error(path.string() + ": " + out->geterror());
    // The in-memory image is RGBA; a stride of 4 floats selects the first `channels` of each pixel.
    bool ok = out->write_image(OIIO::TypeDesc::FLOAT, image.pixels.data(), sizeof(glm::vec4));
    ok = out->close() && ok;
    if (!ok) throw Error(path.string() + ": " + out->geterror());
    file.commit();
}

} // namespace ibl
