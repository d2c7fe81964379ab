// The OpenImageIO module (baker/oiio_module/, built as iblbake_oiio.so): every use of OpenImageIO, loaded
// with dlopen only when a command needs it (an input that is neither OpenEXR nor Radiance, the preview's
// labels), so that the programs start without OpenImageIO's ~260 libraries. Nothing throws across this
// interface: failures come back as false (or null) with the reason in `error`.
#pragma once

#include "../ingest/image_source.h"

#include <memory>
#include <string>

namespace ibl::oiio_module {

// An open image file: ImageSource::readRows without exceptions.
class Image {
  public:
    virtual ~Image() = default;
    virtual bool readRows(int y0, int y1, int begin, int end, float* data, std::string& error) = 0;
};

enum class TextAlign { Left, Centre, Right };

struct Api {
    // Opens `path` (level 0 of its first subimage, colour as stored: unassociated alpha stays unassociated)
    // and describes it in `header`; null with the reason in `error` when it cannot.
    std::unique_ptr<Image> (*openImage)(const std::string& path, ingest::ImageHeader& header,
                                        std::string& error);
    // Draws `text` into an RGB float image (width x height, rows top to bottom) in the TrueType font `font`,
    // `fontSize` pixels high, vertically centred on y and aligned at x as `align` says.
    bool (*drawText)(float* rgb, int width, int height, int x, int y, const std::string& text, int fontSize,
                     const std::string& font, const float colour[3], TextAlign align, std::string& error);
};

// The module in use, loaded on first call (installed beside the program, else the build tree's). Throws
// ibl::Error "<what> needs iblbake's OpenImageIO module: <cause>" when it cannot be loaded.
const Api& api(const std::string& what);

} // namespace ibl::oiio_module

// The one symbol the module exports.
extern "C" const ibl::oiio_module::Api* iblbakeOiioModule();
