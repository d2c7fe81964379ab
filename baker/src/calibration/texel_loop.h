// Loops over a range of a SphereTexels view's texels that read each texel's colour and geometry without
// the per-index cost of its accessors: on a cube, every accessor call divides the index by the face's and
// the cube's size (twice for geometry, once more for colour), several times the cost of the table look-up
// itself; here one division starts the range and each later texel is an increment. The values are the
// accessors' own, bit for bit.
#pragma once

#include "cube_texel_geometry.h"

#include "iblbake/baker/environment_stats.h"

#include <cstddef>

namespace ibl {

// Texel (face, i, j) of cube index (face * n + j) * n + i, advanced one index at a time.
struct CubeTexelWalk {
    int n, face, i, j;
    CubeTexelWalk(std::size_t index, int faceSize)
        : n(faceSize), face(int(index / (std::size_t(faceSize) * std::size_t(faceSize)))),
          i(int(index % std::size_t(faceSize))),
          j(int(index / std::size_t(faceSize) % std::size_t(faceSize))) {}
    void next() {
        if (++i < n) return;
        i = 0;
        if (++j < n) return;
        j = 0;
        ++face;
    }
};

// A cube texel at a walk's position: what SphereTexels' accessors give for its index.
struct WalkedCubeTexel {
    const CubeMap& cube;
    const CubeTexelGeometry& geometry;
    CubeTexelWalk at;
    glm::vec3 rgb() const {
        return glm::vec3(cube.faces[std::size_t(at.face)]
                             .pixels[std::size_t(at.j) * std::size_t(at.n) + std::size_t(at.i)]);
    }
    double solidAngle() const { return geometry.solidAngle(at.i, at.j); }
    glm::dvec3 vectorSolidAngle() const { return geometry.vectorSolidAngle(at.face, at.i, at.j); }
    double vectorSolidAngleY() const { return geometry.vectorSolidAngleY(at.face, at.i, at.j); }
    double upwardCosine() const { return geometry.upwardCosine(at.face, at.i, at.j); }
};

// Any view's texel through its accessors (a lat-long's geometry is computed per pixel anyway).
struct IndexedTexel {
    const SphereTexels& texels;
    std::size_t index;
    glm::vec3 rgb() const { return texels.rgb(index); }
    double solidAngle() const { return texels.solidAngle(index); }
    glm::dvec3 vectorSolidAngle() const { return texels.vectorSolidAngle(index); }
    double vectorSolidAngleY() const { return texels.vectorSolidAngle(index).y; }
    double upwardCosine() const { return texels.upwardCosine(index); }
};

// visit(i, texel) for i in [begin, end) in order, `texel` a WalkedCubeTexel or an IndexedTexel.
template <class Visit>
void forEachTexel(const SphereTexels& texels, std::size_t begin, std::size_t end, Visit&& visit) {
    if (const CubeMap* cube = texels.cubeMap()) {
        WalkedCubeTexel texel{*cube, *texels.cubeGeometry(), CubeTexelWalk(begin, cube->faceSize)};
        for (std::size_t i = begin; i != end; ++i, texel.at.next())
            visit(i, texel);
    } else {
        for (std::size_t i = begin; i != end; ++i)
            visit(i, IndexedTexel{texels, i});
    }
}

} // namespace ibl
