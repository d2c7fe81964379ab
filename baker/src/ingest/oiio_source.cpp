// Every format other than OpenEXR and Radiance, through the OpenImageIO module (oiio_module.h).
#include "../io/oiio_module.h"
#include "image_source.h"

#include "iblbake/core/error.h"

namespace ibl::ingest {

namespace {

class OiioSource final : public ImageSource {
  public:
    OiioSource(const std::filesystem::path& file, const std::string& name) : name_(name) {
        std::string why;
        image_ = oiio_module::api(name + ": reading this format").openImage(file.string(), header_, why);
        if (!image_)
            throw Error(name + ": cannot read as an image" +
                        (why.empty() ? std::string() : ": " + printableForMessage(why)));
    }

    void readRows(int y0, int y1, int begin, int end, float* data) override {
        std::string why;
        if (!image_->readRows(y0, y1, begin, end, data, why))
            throw Error(name_ + ": cannot read pixels: " + printableForMessage(why));
    }

  private:
    std::string name_;
    std::unique_ptr<oiio_module::Image> image_;
};

} // namespace

std::unique_ptr<ImageSource> openOiioSource(const std::filesystem::path& file, const std::string& name) {
    return std::make_unique<OiioSource>(file, name);
}

} // namespace ibl::ingest
