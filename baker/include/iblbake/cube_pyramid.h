// The source cube as the kernels read it: a box-filtered mip pyramid, each face with a one-texel
// border from its neighbours (layout in kernels/cube_sample.h).
#pragma once

#include "iblbake/cubemap.h"

#include <cube_sample.h>

#include <vector>

namespace ibl {

struct CubePyramid {
    CubePyramidLayout layout{};
    std::vector<float> data;
};

// Levels down to 1x1 (at most IBL_MAX_CUBE_LEVELS); each level averages 2x2 texels of the one above.
CubePyramid buildCubePyramid(const CubeMap& base);

} // namespace ibl
