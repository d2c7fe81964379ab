#include "iblbake/core/cube_pyramid.h"
#include "iblbake/core/error.h"

#include <cmath>

namespace ibl {

CubeMap downsampleCube(const CubeMap& above) {
    CubeMap below(std::max(1, above.faceSize / 2));
    const int ratio = above.faceSize / below.faceSize; // 2, or 1 for a 1x1 face
    for (int f = 0; f < 6; ++f)
        for (int y = 0; y < below.faceSize; ++y)
            for (int x = 0; x < below.faceSize; ++x) {
                glm::vec4 sum(0.0f);
                for (int j = 0; j < ratio; ++j)
                    for (int i = 0; i < ratio; ++i)
                        sum += above.faces[f].at(x * ratio + i, y * ratio + j);
                below.faces[f].at(x, y) = sum / float(ratio * ratio);
            }
    return below;
}

CubePyramid buildCubePyramid(const CubeMap& base) {
    if (base.faceSize <= 0 || (base.faceSize & (base.faceSize - 1)) != 0 || base.faceSize > 8192)
        throw Error("cube pyramid: face size " + std::to_string(base.faceSize) +
                    " is not a power of two up to 8192");
    CubePyramid pyramid;
    std::vector<CubeMap> levels{base};
    while (levels.back().faceSize > 1 && levels.size() < IBL_MAX_CUBE_LEVELS)
        levels.push_back(downsampleCube(levels.back()));
    pyramid.layout.baseFaceSize = uint32_t(base.faceSize);
    pyramid.layout.levelCount = uint32_t(levels.size());
    pyramid.data.assign(cubePyramidFloatCount(pyramid.layout), 0.0f);
    for (uint32_t m = 0; m < levels.size(); ++m)
        storeBorderedLevel(levels[m], m, pyramid.layout, pyramid.data.data());
    return pyramid;
}

} // namespace ibl
