// iblbake's OpenImageIO module (baker/src/io/oiio_module.h): any format OpenImageIO reads, and text drawn
// by its render_text (FreeType).
#include "../src/io/oiio_module.h"
#include "../src/io/muted_stderr.h"

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <OpenImageIO/imageio.h>

namespace ibl::oiio_module {

namespace {

class OiioImage final : public Image {
  public:
    OiioImage(std::unique_ptr<OIIO::ImageInput> in) : in_(std::move(in)), spec_(in_->spec()) {}

    bool readRows(int y0, int y1, int begin, int end, float* data, std::string& error) override {
        MutedStderr muted; // libpng prints what geterror() returns as well
        const bool ok =
            spec_.tile_width > 0
                ? in_->read_tiles(0, 0, spec_.x, spec_.x + spec_.width, spec_.y + y0, spec_.y + y1, spec_.z,
                                  spec_.z + 1, begin, end, OIIO::TypeDesc::FLOAT, data)
                : in_->read_scanlines(0, 0, spec_.y + y0, spec_.y + y1, spec_.z, begin, end,
                                      OIIO::TypeDesc::FLOAT, data);
        if (!ok) error = in_->geterror();
        return ok;
    }

  private:
    std::unique_ptr<OIIO::ImageInput> in_;
    OIIO::ImageSpec spec_;
};

std::unique_ptr<Image> openImage(const std::string& path, ingest::ImageHeader& header, std::string& error) {
    // Colour as stored: OIIO would premultiply unassociated alpha (PNG, TIFF), which is wrong where alpha is
    // ignored, and where it is read the premultiplication must follow the colour conversion (ingest.cpp).
    OIIO::ImageSpec config;
    config.attribute("oiio:UnassociatedAlpha", 1);
    MutedStderr muted;
    auto in = OIIO::ImageInput::open(path, &config);
    if (!in) {
        error = OIIO::geterror();
        return nullptr;
    }
    // open() leaves the input at subimage 0, MIP level 0: the full-resolution image.
    const OIIO::ImageSpec& spec = in->spec();
    if (spec.depth > 1) {
        error = "is a volume image, not an environment map";
        return nullptr;
    }
    header.width = spec.width;
    header.height = spec.height;
    for (int c = 0; c < spec.nchannels; ++c)
        header.channels.push_back(spec.channel_name(c));
    header.alphaChannel = spec.alpha_channel;
    header.rowsPerRead = std::max(1, spec.tile_height);
    header.integerPixels = !spec.format.is_floating_point();
    header.unassociatedAlpha = spec.get_int_attribute("oiio:UnassociatedAlpha", 0) != 0;
    header.colorSpace = spec.get_string_attribute("oiio:ColorSpace");
    header.textureFormat = spec.get_string_attribute("textureformat");
    header.upDirection = spec.get_string_attribute("oiio:updirection");
    float chromaticities[8];
    if (spec.getattribute("chromaticities", OIIO::TypeDesc(OIIO::TypeDesc::FLOAT, 8), chromaticities))
        header.chromaticities.assign(chromaticities, chromaticities + 8);
    for (const OIIO::ParamValue& p : spec.extra_attribs)
        if (p.type() == OIIO::TypeDesc::STRING)
            header.stringAttributes.emplace_back(p.name().string(), p.get_string());
    return std::make_unique<OiioImage>(std::move(in));
}

bool drawText(float* rgb, int width, int height, int x, int y, const std::string& text, int fontSize,
              const std::string& font, const float colour[3], TextAlign align, std::string& error) {
    OIIO::ImageBuf canvas(OIIO::ImageSpec(width, height, 3, OIIO::TypeDesc::FLOAT), rgb);
    const auto alignX = align == TextAlign::Left     ? OIIO::ImageBufAlgo::TextAlignX::Left
                        : align == TextAlign::Centre ? OIIO::ImageBufAlgo::TextAlignX::Center
                                                     : OIIO::ImageBufAlgo::TextAlignX::Right;
    if (OIIO::ImageBufAlgo::render_text(canvas, x, y, text, fontSize, font, {colour, 3}, alignX,
                                        OIIO::ImageBufAlgo::TextAlignY::Center))
        return true;
    error = canvas.geterror();
    return false;
}

constexpr Api kApi{openImage, drawText};

} // namespace

} // namespace ibl::oiio_module

extern "C" __attribute__((visibility("default"))) const ibl::oiio_module::Api* iblbakeOiioModule() {
    return &ibl::oiio_module::kApi;
}
