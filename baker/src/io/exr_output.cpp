// OpenEXR output through OpenEXR: encoded in memory, then written atomically (encoded_image.h).
#include "iblbake/baker/exr_output.h"
#include "encoded_image.h"
#include "iblbake/core/error.h"

#include <Imath/half.h>
#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfIO.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfStandardAttributes.h>
#include <OpenEXR/ImfStringAttribute.h>

#include <algorithm>
#include <cstring>

namespace ibl {

namespace {

// An OpenEXR output stream into memory.
class MemoryStream final : public Imf::OStream {
  public:
    MemoryStream() : Imf::OStream("memory") {}
    void write(const char c[], int n) override {
        if (position_ + std::size_t(n) > bytes_.size()) bytes_.resize(position_ + std::size_t(n));
        std::memcpy(bytes_.data() + position_, c, std::size_t(n));
        position_ += std::size_t(n);
    }
    uint64_t tellp() override { return position_; }
    void seekp(uint64_t position) override { position_ = std::size_t(position); }
    std::string_view bytes() const { return {bytes_.data(), bytes_.size()}; }

  private:
    std::vector<char> bytes_;
    std::size_t position_ = 0;
};

} // namespace

void writeExr(const std::filesystem::path& path, const ImageRGBA& image, const ExrOutputOptions& options) {
    if (image.width <= 0 || image.height <= 0)
        throw Error(path.string() + ": refusing to write an empty image");
    const int channels = std::clamp(options.channels, 1, 4);
    const Imf::PixelType type = options.pixelType == PixelType::Half ? Imf::HALF : Imf::FLOAT;
    Imf::Header header(image.width, image.height);
    header.compression() = Imf::ZIP_COMPRESSION;
    if (options.envmap)
        Imf::addEnvmap(header,
                       *options.envmap == ExrEnvmap::LatLong ? Imf::ENVMAP_LATLONG : Imf::ENVMAP_CUBE);
    for (const auto& [key, value] : options.attributes)
        header.insert(key, Imf::StringAttribute(value));
    // OpenEXR writes a channel from a frame buffer of its own type: half channels from a half copy.
    std::vector<Imath::half> halves;
    if (type == Imf::HALF) {
        halves.resize(image.pixels.size() * 4);
        for (std::size_t i = 0; i < image.pixels.size(); ++i)
            for (int c = 0; c < 4; ++c)
                halves[4 * i + std::size_t(c)] = Imath::half(image.pixels[i][c]);
    }
    const char* base = type == Imf::HALF ? reinterpret_cast<const char*>(halves.data())
                                         : reinterpret_cast<const char*>(image.pixels.data());
    const std::size_t pixelBytes = type == Imf::HALF ? 4 * sizeof(Imath::half) : sizeof(glm::vec4);
    const std::size_t channelBytes = pixelBytes / 4;
    Imf::FrameBuffer frame;
    const char* names[4] = {"R", "G", "B", "A"};
    for (int c = 0; c < channels; ++c) {
        header.channels().insert(names[c], Imf::Channel(type));
        frame.insert(names[c], Imf::Slice(type, const_cast<char*>(base + std::size_t(c) * channelBytes),
                                          pixelBytes, pixelBytes * std::size_t(image.width)));
    }
    MemoryStream encoded;
    try {
        Imf::OutputFile out(encoded, header);
        out.setFrameBuffer(frame);
        out.writePixels(image.height);
    } catch (const std::exception& e) {
        throw OutputError(path.string() +
                          ": cannot encode the OpenEXR file: " + printableForMessage(e.what()));
    }
    writeEncodedImage(path, encoded.bytes());
}

} // namespace ibl
