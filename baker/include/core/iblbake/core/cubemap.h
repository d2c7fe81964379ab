// Cube maps in memory. Face order and orientation follow kernels/cube.h (KTX2/Vulkan/OpenGL:
// +X, -X, +Y, -Y, +Z, -Z); each face is a square ImageRGBA whose first row is t = 0.
#pragma once

#include "iblbake/core/image.h"

#include <array>
#include <vector>

namespace ibl {

struct CubeMap {
    int faceSize = 0;
    std::array<ImageRGBA, 6> faces;

    CubeMap() = default;
    explicit CubeMap(int size) : faceSize(size) {
        for (ImageRGBA& f : faces)
            f = ImageRGBA(size, size);
    }
};

// A mip chain: levels[0] is the largest; level m has faceSize max(1, levels[0].faceSize >> m).
struct CubeMapChain {
    std::vector<CubeMap> levels;
};

} // namespace ibl
