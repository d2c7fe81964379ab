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
    pyramid.layout.baseFaceSize = uint32_t(base.faceSize);
    pyramid.layout.levelCount = 1;
    for (int n = base.faceSize; n > 1 && pyramid.layout.levelCount < IBL_MAX_CUBE_LEVELS; n /= 2)
        ++pyramid.layout.levelCount;
    pyramid.data.assign(cubePyramidStorageFloatCount(pyramid.layout), 0.0f);
    // Each level from the one above, stored as it is made. The base is read where it is, not copied: a
    // 256-px cube is 6 MB of memory first touched, a page fault per 4 KB (ingest/read_image.cpp).
    storeBorderedLevel(base, 0, pyramid.layout, pyramid.data.data());
    CubeMap level;
    for (uint32_t m = 1; m < pyramid.layout.levelCount; ++m) {
        level = downsampleCube(m == 1 ? base : level);
        storeBorderedLevel(level, m, pyramid.layout, pyramid.data.data());
    }
    return pyramid;
}

} // namespace ibl
