// Reading an environment image with OpenImageIO: any format it reads, level 0 of the first subimage
// (tiled and MIP-mapped files included), R, G, B (one channel read as grey) and, when asked, A.
#include "../io/muted_stderr.h"
#include "ingest_internal.h"

#include "iblbake/core/error.h"
#include "iblbake/core/input_file.h"
#include "iblbake/core/limits.h"

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

// Pixels read at once (a strip of whole rows, at least one row or one row of tiles): 16 MB of floats.
constexpr std::uint64_t kStripPixels = std::uint64_t(1) << 20;

// Rows [y0, y1) of level 0 (counted from the data window's top), channels [begin, end), as floats.
bool readRows(OIIO::ImageInput& in, const OIIO::ImageSpec& spec, int y0, int y1, int begin, int end,
              float* data) {
    if (spec.tile_width > 0)
        return in.read_tiles(0, 0, spec.x, spec.x + spec.width, spec.y + y0, spec.y + y1, spec.z, spec.z + 1,
                             begin, end, OIIO::TypeDesc::FLOAT, data);
    return in.read_scanlines(0, 0, spec.y + y0, spec.y + y1, spec.z, begin, end, OIIO::TypeDesc::FLOAT, data);
}

// The file's alpha channel: OIIO's alpha_channel, else one named "A"; -1 if none or it is also a colour.
int pickAlpha(const OIIO::ImageSpec& spec, const std::array<int, 3>& rgb) {
    const int alpha = spec.alpha_channel >= 0 ? spec.alpha_channel : findChannel(spec, "A");
    return std::find(rgb.begin(), rgb.end(), alpha) == rgb.end() ? alpha : -1;
}

} // namespace

void takeVisibilityMask(RawImage& image, const RawImage& mask) {
    if (mask.pixels.width != image.pixels.width || mask.pixels.height != image.pixels.height)
        throw Error(mask.file + ": the visibility mask is " + std::to_string(mask.pixels.width) + "x" +
                    std::to_string(mask.pixels.height) + ", but " + image.file + " is " +
                    std::to_string(image.pixels.width) + "x" + std::to_string(image.pixels.height));
    for (std::size_t i = 0; i < image.pixels.pixels.size(); ++i)
        image.pixels.pixels[i].w = mask.pixels.pixels[i].x;
    image.hasAlpha = true;
    image.unassociatedAlpha = true;
}

void checkPixelLimit(const std::string& name, std::uint64_t width, std::uint64_t height) {
    const std::uint64_t maxPixels = limits::maxImagePixels();
    if (height <= maxPixels / width) return;
    const bool overflows = width > UINT64_MAX / height;
    throw Error(name + ": " + std::to_string(width) + "x" + std::to_string(height) + " is " +
                (overflows ? std::string("more than 2^64") : std::to_string(width * height)) +
                " pixels, more than the limit of " + std::to_string(maxPixels) + " (" +
                limits::kMaxImagePixelsVariable + ")");
}

RawImage readImage(const std::filesystem::path& file, const std::function<void(const RawImage&)>& checkHeader,
                   bool readAlpha) {
    const std::string name = printableForMessage(file.string());
    requireRegularFile(file);   // before OIIO probes formats: a device or FIFO would never end
    checkExrHeader(file, name); // before OpenEXR sizes memory from the header's claims

    // Colour as stored: OIIO would premultiply unassociated alpha (PNG, TIFF), which is wrong where alpha is
    // ignored, and where it is read the premultiplication must follow the colour conversion (ingest.cpp).
    OIIO::ImageSpec config;
    config.attribute("oiio:UnassociatedAlpha", 1);
    MutedStderr muted;
    auto in = OIIO::ImageInput::open(file.string(), &config);
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
    // The header's claim is checked before any pixel memory is taken: a damaged or hostile header may
    // claim billions of pixels.
    checkPixelLimit(name, std::uint64_t(spec.width), std::uint64_t(spec.height));
    const std::uint64_t count = std::uint64_t(spec.width) * std::uint64_t(spec.height);

    RawImage raw;
    raw.file = name;
    raw.colorSpace = spec.get_string_attribute("oiio:ColorSpace");
    raw.textureFormat = spec.get_string_attribute("textureformat");
    raw.upDirection = spec.get_string_attribute("oiio:updirection");
    float chroma[8];
    if (spec.getattribute("chromaticities", OIIO::TypeDesc(OIIO::TypeDesc::FLOAT, 8), chroma))
        raw.chromaticities.assign(chroma, chroma + 8);
    raw.integerPixels = !spec.format.is_floating_point();
    raw.pixels.width = spec.width; // the size alone, for checkHeader: no pixels yet
    raw.pixels.height = spec.height;
    if (checkHeader) checkHeader(raw);

    // Only the channels from the lowest to the highest of R, G, B are read, or each of them on its own when
    // they lie far apart (a file with render layers holds many more). Rows are read strip by strip into the
    // image, whose memory is reserved but taken only as rows arrive: a truncated file that claims a huge
    // size fails at its first missing strip having used little, and no second full copy is ever made.
    const std::array<int, 3> rgb = pickChannels(spec);
    const int alpha = readAlpha ? pickAlpha(spec, rgb) : -1;
    raw.hasAlpha = alpha >= 0;
    raw.unassociatedAlpha = raw.hasAlpha && spec.get_int_attribute("oiio:UnassociatedAlpha", 0) != 0;
    std::vector<int> channels(rgb.begin(), rgb.end());
    if (raw.hasAlpha) channels.push_back(alpha);
    const int first = *std::min_element(channels.begin(), channels.end());
    const int span = *std::max_element(channels.begin(), channels.end()) - first + 1;
    const bool together = span <= limits::kMaxChannelsRead;
    const int rowStep = std::max(1, spec.tile_height);
    const int stripRows = rowStep * std::max(1, int(kStripPixels / (std::uint64_t(spec.width) * rowStep)));
    try {
        raw.pixels.pixels.reserve(std::size_t(count));
        std::vector<float> strip;
        for (int y0 = 0; y0 < spec.height; y0 += stripRows) {
            const int y1 = std::min(spec.height, y0 + stripRows);
            const std::size_t offset = raw.pixels.pixels.size();
            const std::size_t n = std::size_t(y1 - y0) * std::size_t(spec.width);
            raw.pixels.pixels.resize(offset + n, glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));
            for (int c = 0; c < (together ? 1 : int(channels.size())); ++c) {
                const int begin = together ? first : channels[std::size_t(c)];
                const int end = together ? first + span : begin + 1;
                strip.resize(n * std::size_t(end - begin));
                if (!readRows(*in, spec, y0, y1, begin, end, strip.data()))
                    throw Error(name + ": cannot read pixels: " + printableForMessage(in->geterror()));
                for (std::size_t i = 0; i < n; ++i) {
                    const float* p = &strip[i * std::size_t(end - begin)];
                    glm::vec4& out = raw.pixels.pixels[offset + i];
                    if (together)
                        out = glm::vec4(p[rgb[0] - first], p[rgb[1] - first], p[rgb[2] - first],
                                        raw.hasAlpha ? p[alpha - first] : 1.0f);
                    else
                        out[c] = p[0];
                }
            }
        }
    } catch (const std::bad_alloc&) {
        throw Error(name + ": not enough memory for " + std::to_string(spec.width) + "x" +
                    std::to_string(spec.height) + " pixels (" + limits::kMaxImagePixelsVariable +
                    " sets a lower limit)");
    }
    in->close();
    return raw;
}

} // namespace ibl::ingest
