// Exact geometry of cube texels on the sphere, tabulated per face size (used by SphereTexels' cube views).
//
// Cube texels are spherical quadrilaterals whose edges are great-circle arcs (straight lines on the face
// plane), so their solid angle has a closed form (the face area element of kernels/cube.h, here in
// double) and so has the integral of the direction over them: Arvo's vector irradiance of a spherical
// polygon, 1/2 sum_k theta_k n_k over its edges (theta_k the arc length, n_k the unit normal of the edge's
// plane). Clipping the face-plane polygon at the horizon (y = 0 is a straight line on every face plane)
// gives the exact upward-cosine weight of a texel that straddles it.
//
// Every face is the same square in its own orthonormal frame (o, u, v), so a texel's solid angle and its
// direction integral in (o, u, v) components are the same on all six faces, and the square's mirror
// symmetries (a -> -a, b -> -b) flip the u and v components: one quadrant of one face is computed, and
// statistics and sun detection read a table instead of evaluating 4 atan2 per solid angle and a spherical
// polygon per direction.
#pragma once

#include "../ingest/ingest_internal.h"

#include <glm/vec3.hpp>

#include <array>
#include <cstddef>
#include <memory>
#include <vector>

namespace ibl {

class CubeTexelGeometry {
  public:
    explicit CubeTexelGeometry(int faceSize);
    // The table of an n-texel face, shared: the one last built for n if it is still that size, else a new
    // one (thread-safe).
    static std::shared_ptr<const CubeTexelGeometry> of(int faceSize);

    int faceSize() const { return n_; }
    double solidAngle(int i, int j) const { return entry(i, j).solidAngle; }
    // Integral of the unit direction over texel (i, j) of `face` (kernels/cube.h orientation).
    glm::dvec3 vectorSolidAngle(int face, int i, int j) const;
    // Its y component alone, the same value to the bit (the same products summed in the same order; one
    // product per statement, since a compiler that fuses a * b + c within an expression would round
    // differently from vectorSolidAngle's vector operations). Inline: sun detection calls it per texel.
    double vectorSolidAngleY(int face, int i, int j) const {
        const glm::dvec3& l = entry(i, j).local;
        const ingest::FaceFrame& f = frames_[std::size_t(face)];
        const double u = i < half_ ? l.y : -l.y, v = j < half_ ? l.z : -l.z;
        const double fromO = f.o.y * l.x, fromU = f.u.y * u, fromV = f.v.y * v;
        return fromO + fromU + fromV;
    }
    // Integral of max(0, d.y) over the texel: its vectorSolidAngle().y above the horizon, 0 below, the
    // clipped polygon's for a texel across it (the middle row of an odd face size).
    double upwardCosine(int face, int i, int j) const;

  private:
    struct Entry {
        double solidAngle;
        glm::dvec3 local; // direction integral in (o, u, v) components
    };
    int n_, half_; // half_: the quadrant's side, ceil(n / 2)
    double step_;  // a texel's side on the face plane, 2 / n
    std::vector<Entry> quadrant_;
    std::array<ingest::FaceFrame, 6> frames_;
    const Entry& entry(int i, int j) const {
        return quadrant_[std::size_t(j < half_ ? j : n_ - 1 - j) * std::size_t(half_) +
                         std::size_t(i < half_ ? i : n_ - 1 - i)];
    }
};

} // namespace ibl
