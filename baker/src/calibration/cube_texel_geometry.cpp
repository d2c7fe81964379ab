// Tabulated cube texel geometry (see cube_texel_geometry.h).
#include "cube_texel_geometry.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <glm/geometric.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <mutex>

namespace ibl {

namespace {

struct FaceSquare {
    double a0, a1, b0, b1;
};

FaceSquare faceSquare(int i, int j, double step) {
    return {-1.0 + i * step, -1.0 + (i + 1) * step, -1.0 + j * step, -1.0 + (j + 1) * step};
}

// A polygon on a face plane, in (a, b) coordinates; at most 5 vertices after one half-plane clip.
struct PlanePolygon {
    std::array<glm::dvec2, 8> v;
    int count = 0;
};

PlanePolygon squarePolygon(const FaceSquare& s) {
    PlanePolygon p;
    p.v[0] = {s.a0, s.b0};
    p.v[1] = {s.a1, s.b0};
    p.v[2] = {s.a1, s.b1};
    p.v[3] = {s.a0, s.b1};
    p.count = 4;
    return p;
}

// Keeps the part where c + g . (a, b) >= 0 (Sutherland-Hodgman against one line).
PlanePolygon clipHalfPlane(const PlanePolygon& in, double c, const glm::dvec2& g) {
    PlanePolygon out;
    for (int k = 0; k < in.count; ++k) {
        const glm::dvec2 p = in.v[std::size_t(k)], q = in.v[std::size_t((k + 1) % in.count)];
        const double fp = c + glm::dot(g, p), fq = c + glm::dot(g, q);
        if (fp >= 0.0) out.v[std::size_t(out.count++)] = p;
        if ((fp >= 0.0) != (fq >= 0.0)) out.v[std::size_t(out.count++)] = p + (q - p) * (fp / (fp - fq));
    }
    return out;
}

// Integral of the unit direction over the spherical polygon under a face-plane polygon (Arvo 1995).
glm::dvec3 polygonVectorSolidAngle(const ingest::FaceFrame& frame, const PlanePolygon& poly) {
    if (poly.count < 3) return glm::dvec3(0.0);
    glm::dvec3 sum(0.0), centre(0.0);
    for (int k = 0; k < poly.count; ++k) {
        const glm::dvec2 p = poly.v[std::size_t(k)], q = poly.v[std::size_t((k + 1) % poly.count)];
        const glm::dvec3 dp = glm::normalize(frame.at(p.x, p.y)), dq = glm::normalize(frame.at(q.x, q.y));
        const glm::dvec3 c = glm::cross(dp, dq);
        const double len = glm::length(c);
        centre += dp;
        if (len > 0.0) sum += (std::atan2(len, glm::dot(dp, dq)) / len) * c;
    }
    sum *= 0.5;
    // The formula's sign follows the polygon's winding; the integral points toward the polygon.
    return glm::dot(sum, centre) < 0.0 ? -sum : sum;
}

// The frame whose components are a face's own: at(a, b) = (1, a, b) in (o, u, v).
const ingest::FaceFrame kLocalFrame{{1.0, 0.0, 0.0}, {0.0, 1.0, 0.0}, {0.0, 0.0, 1.0}};

} // namespace

CubeTexelGeometry::CubeTexelGeometry(int faceSize)
    : n_(faceSize), half_((faceSize + 1) / 2), step_(2.0 / faceSize) {
    for (int face = 0; face < 6; ++face)
        frames_[std::size_t(face)] = ingest::faceFrame(face);
    quadrant_.resize(std::size_t(half_) * std::size_t(half_));
    tbb::parallel_for(tbb::blocked_range<int>(0, half_), [&](const tbb::blocked_range<int>& rows) {
        for (int j = rows.begin(); j != rows.end(); ++j)
            for (int i = 0; i < half_; ++i) {
                const FaceSquare s = faceSquare(i, j, step_);
                Entry& e = quadrant_[std::size_t(j) * std::size_t(half_) + std::size_t(i)];
                e.solidAngle = cubeRectangleSolidAngleF64(s.a0, s.b0, s.a1, s.b1);
                e.local = polygonVectorSolidAngle(kLocalFrame, squarePolygon(s));
            }
    });
}

std::shared_ptr<const CubeTexelGeometry> CubeTexelGeometry::of(int faceSize) {
    static std::mutex mutex;
    static std::shared_ptr<const CubeTexelGeometry> last;
    std::lock_guard<std::mutex> lock(mutex);
    if (!last || last->faceSize() != faceSize) last = std::make_shared<const CubeTexelGeometry>(faceSize);
    return last;
}

glm::dvec3 CubeTexelGeometry::vectorSolidAngle(int face, int i, int j) const {
    const glm::dvec3 l = entry(i, j).local;
    const ingest::FaceFrame& f = frames_[std::size_t(face)];
    // The quadrant's texel mirrored to (i, j): a -> -a flips the u component, b -> -b the v component.
    const double u = i < half_ ? l.y : -l.y, v = j < half_ ? l.z : -l.z;
    return f.o * l.x + f.u * u + f.v * v;
}

double CubeTexelGeometry::upwardCosine(int face, int i, int j) const {
    const ingest::FaceFrame& f = frames_[std::size_t(face)];
    const FaceSquare s = faceSquare(i, j, step_);
    // y(a, b) = o.y + a u.y + b v.y on the face plane, at its extremes over the square.
    const double centreY = f.o.y + 0.5 * (s.a0 + s.a1) * f.u.y + 0.5 * (s.b0 + s.b1) * f.v.y;
    const double reachY = 0.5 * (s.a1 - s.a0) * std::fabs(f.u.y) + 0.5 * (s.b1 - s.b0) * std::fabs(f.v.y);
    if (centreY - reachY >= 0.0) return std::max(0.0, vectorSolidAngle(face, i, j).y);
    if (centreY + reachY <= 0.0) return 0.0;
    const PlanePolygon above = clipHalfPlane(squarePolygon(s), f.o.y, {f.u.y, f.v.y});
    return std::max(0.0, polygonVectorSolidAngle(f, above).y);
}

} // namespace ibl
