// keepSunInLevel0 (specular.h): shared by `iblbake specular`, the scene bake's specular stage, the accuracy
// report and the tests, so that they all bake the product the runtime expects.
#include "iblbake/baker/specular.h"

#include <algorithm>

namespace ibl {

namespace {

// Half floats end at 65,504, B10G11R11 at 65,024 and E5B9G9R9 at 65,408: below 60,000 nothing is clamped.
constexpr float kLargestUnclampedInSmallFloats = 60000.0f;

bool fitsUnclamped(const CubeMap& cube, Ktx2Format format) {
    if (format == Ktx2Format::RGBA32F) return true;
    for (const ImageRGBA& face : cube.faces)
        for (const glm::vec4& texel : face.pixels)
            if (std::max({texel.r, texel.g, texel.b}) > kLargestUnclampedInSmallFloats) return false;
    return true;
}

} // namespace

bool keepSunInLevel0(CubeMapChain& residualChain, const CubeMap& withSun, Ktx2Format format) {
    if (residualChain.levels.empty() || residualChain.levels[0].faceSize != withSun.faceSize ||
        !fitsUnclamped(withSun, format))
        return false;
    residualChain.levels[0] = withSun;
    return true;
}

} // namespace ibl
