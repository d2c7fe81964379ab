// Reading an environment image with OpenImageIO: any format it reads, level 0 of the first subimage
// (tiled and MIP-mapped files included), R, G, B only (alpha ignored, one channel read as grey).
#include "../io/muted_stderr.h"
#include "ingest_internal.h"

#include "iblbake/core/error.h"

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cctype>
#include <system_error>

namespace ibl::ingest {

namespace {

bool equalsNoCase(const std::string& a, const char* b) {
    std::string lb(b);
    return a.size() == lb.size() && std::equal(a.begin(), a.end(), lb.begin(), [](char x, char y) {
               return std::tolower(static_cast<unsigned char>(x)) ==
                      std::tolower(static_cast<unsigned char>(y));
           });
}

int findChannel(const OIIO::ImageSpec& spec, const char* name) {
    for (int c = 0; c < spec.nchannels; ++c)
        if (equalsNoCase(spec.channel_name(c), name)) return c;
    return -1;
}

// Which file channels feed R, G, B: the channels so named, else the first three, else channel 0 as grey.
std::array<int, 3> pickChannels(const OIIO::ImageSpec& spec) {
    std::array<int, 3> rgb = {findChannel(spec, "R"), findChannel(spec, "G"), findChannel(spec, "B")};
    if (rgb[0] >= 0 && rgb[1] >= 0 && rgb[2] >= 0) return rgb;
    if (spec.nchannels >= 3 && spec.alpha_channel != 0 && spec.alpha_channel != 1 && spec.alpha_channel != 2)
        return {0, 1, 2};
    int grey = (spec.alpha_channel == 0 && spec.nchannels > 1) ? 1 : 0; // e.g. "A, Y" in a luminance EXR
    return {grey, grey, grey};
}

} // namespace

RawImage readImage(const std::filesystem::path& file) {
    const std::string name = file.string();
    std::error_code ec;
    if (!std::filesystem::exists(file, ec)) throw Error(name + ": no such file");
    if (std::filesystem::is_directory(file, ec)) throw Error(name + ": is a directory, not an image");

    // Alpha is ignored, so colour must not be premultiplied by it (OIIO would do so for PNG and TIFF).
    OIIO::ImageSpec config;
    config.attribute("oiio:UnassociatedAlpha", 1);
    MutedStderr muted;
    auto in = OIIO::ImageInput::open(name, &config);
    if (!in) {
        std::string why = OIIO::geterror();
        throw Error(name + ": cannot read as an image" + (why.empty() ? std::string() : ": " + why));
    }
    // open() leaves the input at subimage 0, MIP level 0: the full-resolution image.
    const OIIO::ImageSpec spec = in->spec();
    if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0)
        throw Error(name + ": image has no pixels (" + std::to_string(spec.width) + "x" +
                    std::to_string(spec.height) + ")");
    if (spec.depth > 1) throw Error(name + ": is a volume image, not an environment map");

    RawImage raw;
    raw.file = name;
    raw.colorSpace = spec.get_string_attribute("oiio:ColorSpace");
    raw.textureFormat = spec.get_string_attribute("textureformat");
    raw.upDirection = spec.get_string_attribute("oiio:updirection");
    float chroma[8];
    if (spec.getattribute("chromaticities", OIIO::TypeDesc(OIIO::TypeDesc::FLOAT, 8), chroma))
        raw.chromaticities.assign(chroma, chroma + 8);
    raw.integerPixels = !spec.format.is_floating_point();

    const std::size_t count = std::size_t(spec.width) * std::size_t(spec.height);
    std::vector<float> buffer(count * std::size_t(spec.nchannels));
    if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, buffer.data()))
        throw Error(name + ": cannot read pixels: " + in->geterror());
    in->close();

    const std::array<int, 3> rgb = pickChannels(spec);
    raw.pixels = ImageRGBA(spec.width, spec.height);
    for (std::size_t i = 0; i < count; ++i) {
        const float* p = &buffer[i * std::size_t(spec.nchannels)];
        raw.pixels.pixels[i] = glm::vec4(p[rgb[0]], p[rgb[1]], p[rgb[2]], 1.0f);
    }
    return raw;
}

} // namespace ibl::ingest
