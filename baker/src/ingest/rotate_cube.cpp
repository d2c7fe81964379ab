// Rotation of a cube map about +Y, for cube-like inputs (lat-long inputs rotate exactly, by shifting
// longitude, in latlong_to_cube.cpp). Each texel averages 4x4 bilinear lookups at the rotated directions,
// weighted by solid angle: approximate (a box filter of the bilinear reconstruction), which is why a
// rotation is never implicit.
#include "ingest_internal.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

namespace ibl::ingest {

namespace {

// Bilinear lookup within one face, clamped at its edges (texel centres at (i + 0.5) / N).
glm::dvec3 sampleCube(const CubeMap& cube, const glm::dvec3& d) {
    const CubeCoord c = cubeCoordFromDirection(vec3(d));
    const ImageRGBA& face = cube.faces[std::size_t(c.face)];
    const int n = cube.faceSize;
    const double x = std::clamp(double(c.s) * n - 0.5, 0.0, n - 1.0);
    const double y = std::clamp(double(c.t) * n - 0.5, 0.0, n - 1.0);
    const int x0 = std::min(int(x), n - 1), y0 = std::min(int(y), n - 1);
    const int x1 = std::min(x0 + 1, n - 1), y1 = std::min(y0 + 1, n - 1);
    const double fx = x - x0, fy = y - y0;
    auto at = [&](int i, int j) { return glm::dvec3(glm::vec3(face.at(i, j))); };
    return (1 - fy) * ((1 - fx) * at(x0, y0) + fx * at(x1, y0)) +
           fy * ((1 - fx) * at(x0, y1) + fx * at(x1, y1));
}

} // namespace

CubeMap rotateCube(const CubeMap& cube, double rotateRadians) {
    const int n = cube.faceSize;
    constexpr int kSub = 4;
    CubeMap out(n);
    // Content at direction d moves to R(theta) d, so texel d looks up R(-theta) d.
    const double c = std::cos(rotateRadians), s = std::sin(rotateRadians);
    tbb::parallel_for(tbb::blocked_range<int>(0, 6 * n), [&](const tbb::blocked_range<int>& rows) {
        for (int fr = rows.begin(); fr != rows.end(); ++fr) {
            const int face = fr / n, j = fr % n;
            const FaceFrame frame = faceFrame(face);
            for (int i = 0; i < n; ++i) {
                glm::dvec3 sum(0.0);
                double weight = 0.0;
                for (int sj = 0; sj < kSub; ++sj)
                    for (int si = 0; si < kSub; ++si) {
                        const double a = -1.0 + 2.0 * (i + (si + 0.5) / kSub) / n;
                        const double b = -1.0 + 2.0 * (j + (sj + 0.5) / kSub) / n;
                        const glm::dvec3 d = frame.at(a, b);
                        const double w = std::pow(1.0 + a * a + b * b, -1.5); // solid angle per face area
                        const glm::dvec3 src(c * d.x - s * d.z, d.y, s * d.x + c * d.z);
                        sum += w * sampleCube(cube, src);
                        weight += w;
                    }
                out.faces[std::size_t(face)].at(i, j) = glm::vec4(glm::vec3(sum / weight), 1.0f);
            }
        }
    });
    return out;
}

} // namespace ibl::ingest
