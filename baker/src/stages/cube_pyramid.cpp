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
    if (base.faceSize <= 0) throw Error("cube pyramid: empty source cube");
    CubePyramid pyramid;
    std::vector<CubeMap> levels{base};
    while (levels.back().faceSize > 1 && levels.size() < IBL_MAX_CUBE_LEVELS)
        levels.push_back(downsample(levels.back()));
    pyramid.layout.levelCount = uint32_t(levels.size());
    uint32_t offset = 0;
    for (uint32_t m = 0; m < levels.size(); ++m) {
        uint32_t n = uint32_t(levels[m].faceSize);
        pyramid.layout.faceSize[m] = n;
        pyramid.layout.levelOffset[m] = offset;
        offset += 6u * (n + 2u) * (n + 2u) * 3u;
    }
    pyramid.data.assign(offset, 0.0f);
    for (uint32_t m = 0; m < levels.size(); ++m)
        storeLevel(levels[m], m, pyramid);
    return pyramid;
}

} // namespace ibl
