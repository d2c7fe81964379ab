// Reading an environment image: level 0 of the first image (tiled and MIP-mapped files included), R, G, B
// (one channel read as grey) and, when asked, A, from any ImageSource (image_source.h).
#include "image_source.h"
#include "ingest_internal.h"

#include "iblbake/core/error.h"
#include "iblbake/core/input_file.h"
#include "iblbake/core/limits.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cstring>
#include <fstream>

namespace ibl::ingest {

namespace {

bool equalsNoCase(const std::string& a, const char* b) {
    std::string lb(b);
    return a.size() == lb.size() && std::equal(a.begin(), a.end(), lb.begin(), [](char x, char y) {
               return std::tolower(static_cast<unsigned char>(x)) ==
                      std::tolower(static_cast<unsigned char>(y));
           });
}

int findChannel(const ImageHeader& header, const char* name) {
    for (std::size_t c = 0; c < header.channels.size(); ++c)
        if (equalsNoCase(header.channels[c], name)) return int(c);
    return -1;
}

// Which file channels feed R, G, B: the channels so named, else the first three, else channel 0 as grey.
std::array<int, 3> pickChannels(const ImageHeader& header) {
    std::array<int, 3> rgb = {findChannel(header, "R"), findChannel(header, "G"), findChannel(header, "B")};
    if (rgb[0] >= 0 && rgb[1] >= 0 && rgb[2] >= 0) return rgb;
    const int alpha = header.alphaChannel;
    if (header.channels.size() >= 3 && alpha != 0 && alpha != 1 && alpha != 2) return {0, 1, 2};
    int grey = (alpha == 0 && header.channels.size() > 1) ? 1 : 0; // e.g. "A, Y" in a luminance EXR
    return {grey, grey, grey};
}

// Pixels read at once (a strip of whole rows, at least one row or one row of tiles): 768 KB of RGB floats,
// reused strip after strip. Memory the process touches for the first time costs a page fault per 4 KB
// page, 13 us each on the 2-core VM this was measured on while loaded (a 64 MB memset: 220 ms the first
// time, 2.3 ms the second): a strip of the whole 1k sample (6 MB, plus the Radiance reader's 2 MB of RGBE)
// cost ~2,000 of the ~7,900 faults of `iblbake diffuse`, more time than decoding it.
constexpr std::uint64_t kStripPixels = std::uint64_t(1) << 16;
using Range = tbb::blocked_range<std::size_t>;

// The file's alpha channel: the format's own, else one named "A"; -1 if none or it is also a colour.
int pickAlpha(const ImageHeader& header, const std::array<int, 3>& rgb) {
    const int alpha = header.alphaChannel >= 0 ? header.alphaChannel : findChannel(header, "A");
    return std::find(rgb.begin(), rgb.end(), alpha) == rgb.end() ? alpha : -1;
}

} // namespace

std::unique_ptr<ImageSource> openImageSource(const std::filesystem::path& file, const std::string& name) {
    char magic[4] = {};
    std::ifstream(file, std::ios::binary).read(magic, sizeof magic);
    const char exrMagic[4] = {0x76, 0x2f, 0x31, 0x01};
    if (std::memcmp(magic, exrMagic, 4) == 0) {
        checkExrHeader(file, name); // before OpenEXR sizes memory from the header's claims
        return openExrSource(file, name);
    }
    if (magic[0] == '#' && magic[1] == '?') return openRadianceSource(file, name);
    return openOiioSource(file, name);
}

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

OpenedImage openImage(const std::filesystem::path& file,
                      const std::function<void(const RawImage&)>& checkHeader, bool readAlpha) {
    const std::string name = printableForMessage(file.string());
    requireRegularFile(file); // before a format is probed: a device or FIFO would never end
    OpenedImage image;
    image.source = openImageSource(file, name);
    const ImageHeader& header = image.source->header();
    if (header.width <= 0 || header.height <= 0 || header.channels.empty())
        throw Error(name + ": image has no pixels (" + std::to_string(header.width) + "x" +
                    std::to_string(header.height) + ")");
    // The header's claim is checked before any pixel memory is taken: a damaged or hostile header may
    // claim billions of pixels.
    checkPixelLimit(name, std::uint64_t(header.width), std::uint64_t(header.height));

    RawImage& raw = image.raw;
    raw.file = name;
    raw.colorSpace = header.colorSpace;
    raw.textureFormat = header.textureFormat;
    raw.upDirection = header.upDirection;
    raw.chromaticities = header.chromaticities;
    raw.integerPixels = header.integerPixels;
    raw.pixels.width = header.width; // the size alone, for checkHeader: no pixels yet
    raw.pixels.height = header.height;
    if (checkHeader) checkHeader(raw);
    image.rgb = pickChannels(header);
    image.alpha = readAlpha ? pickAlpha(header, image.rgb) : -1;
    raw.hasAlpha = image.alpha >= 0;
    raw.unassociatedAlpha = raw.hasAlpha && header.unassociatedAlpha;
    return image;
}

void readRgbaRows(OpenedImage& image, int y0, int y1, glm::vec4* out, std::vector<float>& strip,
                  const std::function<void(glm::vec4*, std::size_t)>& written) {
    // Only the channels from the lowest to the highest of R, G, B (and A) are read, or each of them on its
    // own when they lie far apart (a file with render layers holds many more).
    const std::array<int, 3>& rgb = image.rgb;
    const int alpha = image.alpha;
    std::vector<int> channels(rgb.begin(), rgb.end());
    if (alpha >= 0) channels.push_back(alpha);
    const int first = *std::min_element(channels.begin(), channels.end());
    const int span = *std::max_element(channels.begin(), channels.end()) - first + 1;
    const bool together = span <= limits::kMaxChannelsRead;
    const std::size_t n = std::size_t(y1 - y0) * std::size_t(image.raw.pixels.width);
    if (!together) std::fill(out, out + n, glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));
    const int reads = together ? 1 : int(channels.size());
    for (int c = 0; c < reads; ++c) {
        const int begin = together ? first : channels[std::size_t(c)];
        const int end = together ? first + span : begin + 1;
        strip.resize(n * std::size_t(end - begin));
        image.source->readRows(y0, y1, begin, end, strip.data());
        tbb::parallel_for(Range(0, n, kPixelsPerTask), [&](const Range& r) {
            for (std::size_t i = r.begin(); i != r.end(); ++i) {
                const float* p = &strip[i * std::size_t(end - begin)];
                if (together)
                    out[i] = glm::vec4(p[rgb[0] - first], p[rgb[1] - first], p[rgb[2] - first],
                                       alpha >= 0 ? p[alpha - first] : 1.0f);
                else
                    out[i][c] = p[0];
            }
            if (written && c == reads - 1) written(out + r.begin(), r.size());
        });
    }
}

void readPixels(OpenedImage& image, bool keepRgbe) {
    RawImage& raw = image.raw;
    ImageSource& source = *image.source;
    const ImageHeader& header = source.header();
    const std::uint64_t count = std::uint64_t(header.width) * std::uint64_t(header.height);
    // Rows are read strip by strip into the image, whose memory is reserved but taken only as rows arrive: a
    // truncated file that claims a huge size fails at its first missing strip having used little, and no
    // second full copy is ever made.
    const int rowStep = header.rowsPerRead;
    const int stripRows = rowStep * std::max(1, int(kStripPixels / (std::uint64_t(header.width) * rowStep)));
    const auto outOfMemory = [&] {
        return Error(raw.file + ": not enough memory for " + std::to_string(header.width) + "x" +
                     std::to_string(header.height) + " pixels (" + limits::kMaxImagePixelsVariable +
                     " sets a lower limit)");
    };
    try {
        if (keepRgbe && source.storesRgbe()) {
            raw.rgbe.width = header.width;
            raw.rgbe.height = header.height;
            raw.rgbe.pixels.reserve(std::size_t(count));
            for (int y0 = 0; y0 < header.height; y0 += stripRows) {
                const int y1 = std::min(header.height, y0 + stripRows);
                const std::size_t offset = raw.rgbe.pixels.size();
                raw.rgbe.pixels.resize(offset + std::size_t(y1 - y0) * std::size_t(header.width));
                source.readRgbeRows(y0, y1, &raw.rgbe.pixels[offset]);
            }
            return;
        }
        raw.pixels.pixels.reserve(std::size_t(count));
        std::vector<float> strip;
        for (int y0 = 0; y0 < header.height; y0 += stripRows) {
            const int y1 = std::min(header.height, y0 + stripRows);
            const std::size_t offset = raw.pixels.pixels.size();
            raw.pixels.pixels.resize(offset + std::size_t(y1 - y0) * std::size_t(header.width));
            readRgbaRows(image, y0, y1, &raw.pixels.pixels[offset], strip);
        }
    } catch (const std::bad_alloc&) {
        throw outOfMemory();
    }
}

RawImage readImage(const std::filesystem::path& file, const std::function<void(const RawImage&)>& checkHeader,
                   bool readAlpha, bool keepRgbe) {
    OpenedImage image = openImage(file, checkHeader, readAlpha);
    readPixels(image, keepRgbe);
    return std::move(image.raw);
}

void decodeKeptRgbe(RawImage& image) {
    const std::vector<RgbePixel>& stored = image.rgbe.pixels;
    if (stored.empty()) return;
    image.pixels.pixels.resize(stored.size());
    tbb::parallel_for(Range(0, stored.size(), kPixelsPerTask), [&](const Range& r) {
        for (std::size_t i = r.begin(); i != r.end(); ++i)
            image.pixels.pixels[i] = decodeRgbe(stored[i]);
    });
    image.rgbe = {};
}

std::vector<std::pair<std::string, std::string>> readStringAttributes(const std::filesystem::path& file) {
    const std::string name = printableForMessage(file.string());
    requireRegularFile(file);
    return openImageSource(file, name)->header().stringAttributes;
}

} // namespace ibl::ingest
