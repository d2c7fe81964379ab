// The source cube as the kernels read it: a box-filtered mip pyramid, each face with a one-texel
// border from its neighbours (layout in kernels/cube_sample.h).
#pragma once

#include "iblbake/core/cubemap.h"

#include <cube_sample.h>

#include <algorithm>
#include <cstdint>
#include <vector>

namespace ibl {

struct CubePyramid {
    CubePyramidLayout layout{};
    std::vector<float> data;
};

// Visits every texel of level `index` of a pyramid with `layout`, borders included: visit(o, v) with o the
// texel's RGB float index (cubeBorderedTexelIndex) and v its value, each face's border being the texel of
// the neighbouring face that the border texel's centre direction falls on. Header-only, so that the
// runtime module (which does not link the baker) builds its pyramids the same way.
template <class Visit>
void forEachBorderedTexel(const CubeMap& level, std::uint32_t index, const CubePyramidLayout& layout,
                          Visit visit) {
    const int n = level.faceSize;
    for (int face = 0; face < 6; ++face)
        for (int y = -1; y <= n; ++y)
            for (int x = -1; x <= n; ++x) {
                glm::vec4 v;
                if (x >= 0 && x < n && y >= 0 && y < n) {
                    v = level.faces[face].at(x, y);
                } else {
                    CubeCoord c = cubeCoordFromDirection(
                        cubeFaceDirection(face, (float(x) + 0.5f) / float(n), (float(y) + 0.5f) / float(n)));
                    int sx = std::clamp(int(c.s * float(n)), 0, n - 1),
                        sy = std::clamp(int(c.t * float(n)), 0, n - 1);
                    v = level.faces[c.face].at(sx, sy);
                }
                visit(cubeBorderedTexelIndex(layout, index, face, x, y), v);
            }
}

// Copies the RGB of level `index` into the pyramid `data` (3 floats per texel).
inline void storeBorderedLevel(const CubeMap& level, std::uint32_t index, const CubePyramidLayout& layout,
                               float* data) {
    forEachBorderedTexel(level, index, layout, [&](std::uint32_t o, const glm::vec4& v) {
        data[o] = v.x;
        data[o + 1] = v.y;
        data[o + 2] = v.z;
    });
}

// The next level of a box-filtered pyramid: each texel averages 2x2 texels of `above` (a 1x1 face stays).
CubeMap downsampleCube(const CubeMap& above);

// Levels down to 1x1 (at most IBL_MAX_CUBE_LEVELS); each level averages 2x2 texels of the one above.
CubePyramid buildCubePyramid(const CubeMap& base);

} // namespace ibl
