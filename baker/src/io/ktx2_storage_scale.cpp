// The storage scale of a product file (iblbake/ktx2/storage_scale.h).
#include "iblbake/ktx2/storage_scale.h"

#include "iblbake/core/error.h"
#include "small_float.h"

#include <cfloat>
#include <cmath>
#include <string>

namespace ibl {

glm::vec3 ktx2LargestValues(Ktx2Format format) {
    switch (format) {
    case Ktx2Format::RGBA16F:
    case Ktx2Format::BC6H: // unsigned halves
    case Ktx2Format::BC6HFast:
    case Ktx2Format::BC6HBest:
        return glm::vec3(smallfloat::kHalfMax);
    case Ktx2Format::B10G11R11:
        return glm::vec3(smallfloat::kFloat11Max, smallfloat::kFloat11Max, smallfloat::kFloat10Max);
    case Ktx2Format::E5B9G9R9:
        return glm::vec3(smallfloat::kRgb9e5Max);
    default:
        return glm::vec3(FLT_MAX);
    }
}

double ktx2StorageScale(const Ktx2Image& image) {
    const auto it = image.keyValues.find(kStorageScaleKey);
    if (it == image.keyValues.end()) return 1.0;
    double scale = 0.0;
    std::size_t used = 0;
    try {
        scale = std::stod(it->second, &used);
    } catch (const std::exception&) {
        used = 0;
    }
    if (used == 0 || used != it->second.size() || !std::isfinite(scale) || !(scale > 0.0))
        throw Error(std::string(kStorageScaleKey) + ": " + valueForMessage(it->second) +
                    " is not a positive finite number");
    return scale;
}

void unscaleKtx2Texels(Ktx2Image& image) {
    const double scale = ktx2StorageScale(image);
    if (scale == 1.0) return;
    const float inverse = float(1.0 / scale); // a power of two when iblbake wrote it: exact
    for (std::vector<ImageRGBA>& level : image.levels)
        for (ImageRGBA& face : level)
            for (glm::vec4& texel : face.pixels) {
                texel.r *= inverse;
                texel.g *= inverse;
                texel.b *= inverse;
            }
}

} // namespace ibl
