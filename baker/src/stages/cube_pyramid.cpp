#include "iblbake/cube_pyramid.h"
#include "iblbake/error.h"

#include <tbb/parallel_for.h>

#include <cmath>

namespace ibl {
namespace {

CubeMap downsample(const CubeMap& above) {
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

// Copies one level into the flat array and fills each face's border with the texel of the
// neighbouring face that the border texel's centre direction falls on.
void storeLevel(const CubeMap& level, uint32_t index, CubePyramid& pyramid) {
    const int n = level.faceSize;
    tbb::parallel_for(0, 6, [&](int face) {
        for (int y = -1; y <= n; ++y)
            for (int x = -1; x <= n; ++x) {
                glm::vec4 v;
                if (x >= 0 && x < n && y >= 0 && y < n) {
                    v = level.faces[face].at(x, y);
                } else {
                    vec3 d =
                        cubeFaceDirection(face, (float(x) + 0.5f) / float(n), (float(y) + 0.5f) / float(n));
                    CubeCoord c = cubeCoordFromDirection(d);
                    int sx = std::clamp(int(c.s * float(n)), 0, n - 1),
                        sy = std::clamp(int(c.t * float(n)), 0, n - 1);
                    v = level.faces[c.face].at(sx, sy);
                }
                uint32_t o = cubeBorderedTexelIndex(pyramid.layout, index, face, x, y);
                pyramid.data[o] = v.x;
                pyramid.data[o + 1] = v.y;
                pyramid.data[o + 2] = v.z;
            }
    });
}

} // namespace

CubePyramid buildCubePyramid(const CubeMap& base) {
    if (base.faceSize <= 0 || (base.faceSize & (base.faceSize - 1)) != 0 || base.faceSize > 8192)
        throw Error("cube pyramid: face size " + std::to_string(base.faceSize) +
                    " is not a power of two up to 8192");
    CubePyramid pyramid;
    std::vector<CubeMap> levels{base};
    while (levels.back().faceSize > 1 && levels.size() < IBL_MAX_CUBE_LEVELS)
        levels.push_back(downsample(levels.back()));
    pyramid.layout.baseFaceSize = uint32_t(base.faceSize);
    pyramid.layout.levelCount = uint32_t(levels.size());
    pyramid.data.assign(cubePyramidFloatCount(pyramid.layout), 0.0f);
    for (uint32_t m = 0; m < levels.size(); ++m)
        storeLevel(levels[m], m, pyramid);
    return pyramid;
}

} // namespace ibl
