#include "iblbake/baker/exr_output.h"
#include "iblbake/core/error.h"
#include "iblbake/ktx2/atomic_file.h"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <string_view>
#include <vector>

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

    // Encoded in memory and written by writeFileBytes, so that a full disk or a read-only directory is
    // reported with the system's reason and the target's name (OpenEXR's own message names the temporary
    // file and not the cause).
    std::vector<unsigned char> encoded;
    OIIO::Filesystem::IOVecOutput memory(encoded);
    auto out = OIIO::ImageOutput::create("exr", &memory);
    if (!out) throw OutputError(path.string() + ": cannot create an OpenEXR writer: " + OIIO::geterror());
    void* proxy = &memory;
    spec.attribute("oiio:ioproxy", OIIO::TypeDesc::PTR, &proxy);
    if (!out->open(file.tempPath().string(), spec)) throw OutputError(path.string() + ": " + out->geterror());
    // The in-memory image is RGBA; a stride of 4 floats selects the first `channels` of each pixel.
    bool ok = out->write_image(OIIO::TypeDesc::FLOAT, image.pixels.data(), sizeof(glm::vec4));
    ok = out->close() && ok;
    if (!ok) throw OutputError(path.string() + ": " + out->geterror());
    writeFileBytes(file.tempPath(),
                   std::string_view(reinterpret_cast<const char*>(encoded.data()), encoded.size()),
                   path.string());
    file.commit();
}

} // namespace ibl
