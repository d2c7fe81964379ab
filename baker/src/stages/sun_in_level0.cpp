// keepSunInLevel0 (specular.h): shared by `iblbake specular`, the scene bake's specular stage, the accuracy
// report and the tests, so that they all bake the product the runtime expects.
#include "iblbake/baker/specular.h"
#include "iblbake/ktx2/storage_scale.h"

#include <cmath>

namespace ibl {

namespace {

// Whether clamping to the format's range leaves every finite channel as it is.
bool fitsUnclamped(const CubeMap& cube, Ktx2Format format) {
    const glm::vec3 largest = ktx2LargestValues(format);
    for (const ImageRGBA& face : cube.faces)
        for (const glm::vec4& texel : face.pixels)
            for (int c = 0; c < 3; ++c)
                if (std::isfinite(texel[c]) && texel[c] > largest[c]) return false;
    return true;
}

} // namespace

bool keepSunInLevel0(CubeMapChain& residualChain, const CubeMap& withSun, Ktx2Format format,
                     bool clampToFormat) {
    // BC6H's blocks spread a sun disk's error over the sky beside it (the park sample's sun came back with
    // more than 1% of its illuminance off), so a BC6H level 0 keeps the residual like the rest of the chain.
    if (residualChain.levels.empty() || residualChain.levels[0].faceSize != withSun.faceSize ||
        (clampToFormat && !fitsUnclamped(withSun, format)) || isBc6h(format))
        return false;
    residualChain.levels[0] = withSun;
    return true;
}

} // namespace ibl
