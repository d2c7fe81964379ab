// OpenEXR files through OpenEXR itself (image_source.h): the first part, level 0 of a tiled or MIP-mapped
// file, its data window. The header was walked by checkExrHeader (exr_header.cpp) before OpenEXR sees it.
// Metadata as OpenImageIO reports it, so that files read the same as before this reader existed: colour
// space "Linear", the envmap attribute as textureformat "LatLong Environment" (up direction "y") or
// "CubeFace Environment", chromaticities, and string attributes by name.
#include "image_source.h"

#include "iblbake/core/error.h"

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfCompression.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfStandardAttributes.h>
#include <OpenEXR/ImfStringAttribute.h>
#include <OpenEXR/ImfThreading.h>

#include <algorithm>
#include <mutex>
#include <thread>

namespace ibl::ingest {

namespace {

// OpenEXR decodes chunks on its global thread pool; without one it decodes on the caller's thread alone.
void startOpenExrThreads() {
    static std::once_flag once;
    std::call_once(once,
                   [] { Imf::setGlobalThreadCount(int(std::max(1u, std::thread::hardware_concurrency()))); });
}

// Scan lines a chunk of a scan-line file holds, by its compression (the OpenEXR file layout, "Scan Line
// Blocks"); a read of part of a chunk decodes all of it.
int linesPerChunk(Imf::Compression compression) {
    switch (compression) {
    case Imf::ZIP_COMPRESSION:
    case Imf::PXR24_COMPRESSION:
        return 16;
    case Imf::PIZ_COMPRESSION:
    case Imf::B44_COMPRESSION:
    case Imf::B44A_COMPRESSION:
    case Imf::DWAA_COMPRESSION:
        return 32;
    case Imf::DWAB_COMPRESSION:
        return 256;
    default: // none, RLE, ZIPS
        return 1;
    }
}

std::string textOf(const std::exception& e) {
    return printableForMessage(e.what());
}

class ExrSource final : public ImageSource {
  public:
    ExrSource(const std::filesystem::path& file, const std::string& name) : name_(name) {
        startOpenExrThreads();
        try {
            in_ = std::make_unique<Imf::InputFile>(file.c_str());
        } catch (const std::exception& e) {
            throw Error(name + ": cannot read as OpenEXR: " + textOf(e));
        }
        const Imf::Header& h = in_->header();
        dataWindow_ = h.dataWindow();
        header_.width = dataWindow_.max.x - dataWindow_.min.x + 1;
        header_.height = dataWindow_.max.y - dataWindow_.min.y + 1;
        header_.rowsPerRead = h.hasTileDescription() ? std::max(1, int(h.tileDescription().ySize))
                                                     : linesPerChunk(h.compression());
        bool allIntegers = true;
        for (auto c = h.channels().begin(); c != h.channels().end(); ++c) {
            if (c.channel().xSampling != 1 || c.channel().ySampling != 1)
                throw Error(name + ": channel " + printableForMessage(c.name()) +
                            " is subsampled, which is not supported");
            if (std::string(c.name()) == "A") header_.alphaChannel = int(header_.channels.size());
            header_.channels.emplace_back(c.name());
            allIntegers = allIntegers && c.channel().type == Imf::UINT;
        }
        header_.integerPixels = allIntegers;
        header_.colorSpace = "Linear";
        if (Imf::hasEnvmap(h)) {
            if (Imf::envmapAttribute(h).value() == Imf::ENVMAP_LATLONG) {
                header_.textureFormat = "LatLong Environment";
                header_.upDirection = "y";
            } else if (Imf::envmapAttribute(h).value() == Imf::ENVMAP_CUBE) {
                header_.textureFormat = "CubeFace Environment";
            }
        }
        if (Imf::hasChromaticities(h)) {
            const Imf::Chromaticities& c = Imf::chromaticitiesAttribute(h).value();
            header_.chromaticities = {c.red.x,  c.red.y,  c.green.x, c.green.y,
                                      c.blue.x, c.blue.y, c.white.x, c.white.y};
        }
        for (auto a = h.begin(); a != h.end(); ++a) {
            const auto* text = dynamic_cast<const Imf::StringAttribute*>(&a.attribute());
            if (!text) continue;
            const std::string key = a.name();
            if (key == "oiio:ColorSpace") header_.colorSpace = text->value();
            if (key == "oiio:updirection") header_.upDirection = text->value();
            header_.stringAttributes.emplace_back(key, text->value());
        }
    }

    bool readsRowsInAnyOrder() const override { return true; }

    void readRows(int y0, int y1, int begin, int end, float* data) override {
        const std::size_t xStride = sizeof(float) * std::size_t(end - begin);
        const Imath::Box2i rows(Imath::V2i(dataWindow_.min.x, dataWindow_.min.y + y0),
                                Imath::V2i(dataWindow_.max.x, dataWindow_.min.y + y1 - 1));
        Imf::FrameBuffer frame;
        for (int c = begin; c < end; ++c)
            frame.insert(header_.channels[std::size_t(c)],
                         Imf::Slice::Make(Imf::FLOAT, data + (c - begin), rows, xStride,
                                          xStride * std::size_t(header_.width)));
        try {
            in_->setFrameBuffer(frame);
            in_->readPixels(rows.min.y, rows.max.y);
        } catch (const std::exception& e) {
            throw Error(name_ + ": cannot read pixels: " + textOf(e));
        }
    }

  private:
    std::string name_;
    std::unique_ptr<Imf::InputFile> in_;
    Imath::Box2i dataWindow_;
};

} // namespace

std::unique_ptr<ImageSource> openExrSource(const std::filesystem::path& file, const std::string& name) {
    return std::make_unique<ExrSource>(file, name);
}

} // namespace ibl::ingest
