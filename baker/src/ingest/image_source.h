// Decoders of image files at the edge of ingest: a header, then rows of channels as floats. OpenEXR files
// are read by OpenEXR and Radiance files by radiance_source.cpp, so a bake from either never loads
// OpenImageIO; every other format goes through the OpenImageIO module (oiio_module.h), loaded on demand.
// readImage (read_image.cpp) picks the channels, checks the limits and assembles the image on top.
#pragma once

#include "rgbe.h"

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace ibl::ingest {

// Pixels per TBB task where ingest converts or copies pixels in parallel (the Radiance decode's floats,
// a strip's copy into the image): large enough that a task outweighs its scheduling.
inline constexpr std::size_t kPixelsPerTask = 16 * 1024;

struct ImageHeader {
    int width = 0, height = 0;         // level 0 of the first image (the data window, for OpenEXR)
    std::vector<std::string> channels; // names, in the order readRows counts channels
    int alphaChannel = -1;             // the format's own alpha channel, -1 if it names none
    int rowsPerRead = 1;               // rows of a chunk (OpenEXR's tile height or lines per chunk), which
                                       // is decoded whole: strips are multiples of it
    bool integerPixels = false;        // stored as integers: display-encoded
    bool unassociatedAlpha = false;    // colour not premultiplied by alpha (PNG, some TIFF)
    std::string colorSpace;            // what the format says ("Linear" for OpenEXR), "" if nothing
    std::string textureFormat;         // "LatLong Environment" / "CubeFace Environment" or ""
    std::string upDirection;           // "y" for OpenEXR lat-long envmaps, else the file's own, or ""
    std::vector<float> chromaticities; // 8 values (red, green, blue, white x and y) if the file has them
    std::vector<std::pair<std::string, std::string>> stringAttributes; // the file's text metadata
};

class ImageSource {
  public:
    virtual ~ImageSource() = default;
    const ImageHeader& header() const { return header_; }
    // Rows [y0, y1) of level 0, channels [begin, end), as floats interleaved per pixel into `data`. Rows may
    // be asked for again (one channel at a time) but never before rows already read. Throws ibl::Error
    // "<file>: cannot read pixels: <cause>".
    virtual void readRows(int y0, int y1, int begin, int end, float* data) = 0;
    // Whether readRows takes rows in any order (OpenEXR: each chunk is found by the file's offset table).
    virtual bool readsRowsInAnyOrder() const { return false; }
    // Whether the file stores Radiance RGBE pixels, which readRgbeRows gives as stored (rgbe.h).
    virtual bool storesRgbe() const { return false; }
    // Rows [y0, y1) of a source that storesRgbe(), after the rows already read; not mixed with readRows.
    virtual void readRgbeRows(int /*y0*/, int /*y1*/, RgbePixel* /*data*/) {
        throw std::logic_error("readRgbeRows: the source stores no RGBE pixels");
    }

  protected:
    ImageHeader header_;
};

// The source for `file` by its first bytes: OpenEXR's magic number, Radiance's "#?", else OpenImageIO.
// `name` is the file as messages show it. Throws ibl::Error "<name>: ..." when the file cannot be opened.
std::unique_ptr<ImageSource> openImageSource(const std::filesystem::path& file, const std::string& name);

std::unique_ptr<ImageSource> openExrSource(const std::filesystem::path& file, const std::string& name);
std::unique_ptr<ImageSource> openRadianceSource(const std::filesystem::path& file, const std::string& name);
std::unique_ptr<ImageSource> openOiioSource(const std::filesystem::path& file, const std::string& name);

} // namespace ibl::ingest
