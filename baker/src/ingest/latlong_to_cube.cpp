// Lat-long -> cube resampling that is exact in area.
//
// In the coordinates (longitude phi, z = sin(latitude)) the solid angle is dphi * dz (Lambert's
// cylindrical equal-area projection), and a lat-long pixel is an axis-aligned rectangle in which the
// image is constant (the placement's pixel grid, latlong_pixels.h). A cube texel, seen from the
// centre, is a convex spherical quadrilateral: every meridian crosses it in one arc [z_lo(phi), z_hi(phi)],
// found by clipping the meridian's half-plane against the texel square on the face plane. So
//
//     energy(texel) = integral over phi of  integral_{z_lo(phi)}^{z_hi(phi)} L(phi, z) dz  dphi,
//
// where the inner integral is a sum over the pixel column's rows (exact), and the outer one is split at
// pixel column edges and at the texel corners' longitudes (where z_lo, z_hi have kinks) and done by
// Gauss-Legendre quadrature on each piece. The texel's value is energy / area, the area being the same
// quadrature of z_hi - z_lo: a constant environment gives a constant cube to rounding, and a one-pixel
// sun keeps its energy (vertical texel edges on the side faces are meridians, so there the split of a
// pixel between texels is exact; elsewhere only the quadrature of a smooth edge curve is approximate).
//
// The geometry (cuts, meridian clips, rows crossed) is the costly part, and most texels share it with
// others: the cube and the lat-long grid are both unchanged by the mirror y -> -y (row edges are symmetric
// about the equator in either placement) and, when the columns are (Centre placement, width a multiple of
// 4), by a quarter turn about +Y, which shifts u by 1/4 (width/4 columns), and then, without a rotation, by
// the reflections in vertical planes that the turns generate from x -> -x, which reverse u (column c to
// a fixed column minus c). A texel's mirror image integrates the same rows mirrored (H-1-r), a quarter turn
// the columns shifted, a reflection the columns reversed, with the same weights. So for an even face size
// the geometry is computed for one texel of each such set (its orbit: 16 texels, 8 without the reflections,
// 2 without the turns) and its weights applied to all of them: a sixteenth of the cube (a quadrant of a
// side face's upper half and half a quadrant of +Y) instead of all of it. The arithmetic is symmetric too:
// on the sample and the tests' images every texel has the bits it has when computed on its own.
//
// A streamed ingest (resampleLatLongBlocks) computes the same texels with the same arithmetic from the rows
// it holds: in slabs by the last block of rows each reads, a slab's blocks decoded while the slab before it
// is resampled, so the cube has the whole image's bits.
#include "iblbake/core/numeric.h"
#include "ingest_internal.h"

#include "iblbake/core/error.h"

#include <cube.h>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_group.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <span>
#include <stdexcept>
#include <string>

namespace ibl {

namespace ingest {

namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;

// 2-point Gauss-Legendre rule on [-1, 1] (exact for cubics; Abramowitz & Stegun, table 25.4).
constexpr int kOrder = 2;
constexpr double kNodes[kOrder] = {-0.5773502691896258, 0.5773502691896258};
constexpr double kWeights[kOrder] = {1.0, 1.0};

// acos within 6.7e-5 rad (Abramowitz & Stegun 4.4.45), a fraction of a row even for 16k-pixel-high
// lat-longs; 3-4x cheaper than std::acos, which the row search called twice per quadrature node.
double approximateAcos(double x) {
    const double ax = std::fabs(x);
    const double r =
        std::sqrt(1.0 - ax) * (1.5707288 + ax * (-0.2121144 + ax * (0.0742610 - ax * 0.0187293)));
    return x < 0.0 ? kPi - r : r;
}

double longitude(const glm::dvec3& d) {
    return std::atan2(d.x, d.z);
}

struct Square {
    double a0, a1, b0, b1;
};

// The meridian at longitude phi on a face plane: the line A a + B b + C = 0 as the point (pa, pb) plus
// tau (ta, tb), and its half-plane of directions alpha + beta tau >= 0. It depends on the face and phi only,
// so texels that share a longitude (a side face's column) share it.
struct FaceMeridian {
    bool meets = false; // false: the meridian plane is parallel to the face
    double pa, pb, ta, tb;
    double alpha, beta;
};

FaceMeridian faceMeridian(const FaceFrame& f, double phi) {
    const glm::dvec3 n(std::cos(phi), 0.0, -std::sin(phi)); // normal of the meridian's plane
    const glm::dvec3 m(std::sin(phi), 0.0, std::cos(phi));  // the meridian's horizontal direction
    // Plane: A a + B b + C = 0 on the face plane; half-plane: P + Q a + R b >= 0.
    const double A = glm::dot(n, f.u), B = glm::dot(n, f.v), C = glm::dot(n, f.o);
    const double P = glm::dot(m, f.o), Q = glm::dot(m, f.u), R = glm::dot(m, f.v);
    const double len2 = A * A + B * B;
    FaceMeridian mer;
    if (len2 < 1e-24) return mer;
    mer.meets = true;
    mer.pa = -C * A / len2;
    mer.pb = -C * B / len2;
    mer.ta = -B;
    mer.tb = A;
    mer.alpha = P + Q * mer.pa + R * mer.pb;
    mer.beta = Q * mer.ta + R * mer.tb;
    return mer;
}

// The arc [zLo, zHi] of the meridian inside the texel; false when they do not meet.
bool clipMeridian(const FaceFrame& f, const Square& sq, const FaceMeridian& mer, double& zLo, double& zHi) {
    if (!mer.meets) return false;
    const double pa = mer.pa, pb = mer.pb, ta = mer.ta, tb = mer.tb;
    double lo = -1e300, hi = 1e300;
    // Constraint alpha + beta * tau >= 0 (Liang-Barsky).
    auto limit = [&](double alpha, double beta) {
        if (std::fabs(beta) < 1e-300) {
            if (alpha < 0.0) hi = -1e300;
        } else if (beta > 0.0) {
            lo = std::max(lo, -alpha / beta);
        } else {
            hi = std::min(hi, -alpha / beta);
        }
    };
    limit(pa - sq.a0, ta);
    limit(sq.a1 - pa, -ta);
    limit(pb - sq.b0, tb);
    limit(sq.b1 - pb, -tb);
    limit(mer.alpha, mer.beta);
    if (!(lo < hi)) return false;
    const glm::dvec3 d0 = f.at(pa + lo * ta, pb + lo * tb), d1 = f.at(pa + hi * ta, pb + hi * tb);
    const double z0 = d0.y / glm::length(d0), z1 = d1.y / glm::length(d1);
    zLo = std::min(z0, z1);
    zHi = std::max(z0, z1);
    return true;
}

// Pixel edges of a row or column of n pixels in the placement's grid (latlong_pixels.h).
std::vector<double> latLongEdges(LatLongPixels placement, int n) {
    std::vector<double> e(std::size_t(n) + 1);
    for (int k = 0; k <= n; ++k)
        e[std::size_t(k)] = latLongPixelEdge(placement, k, n);
    return e;
}

// The lat-long's pixel grid (the pixels themselves are read by integrateColumn).
class LatLongGrid {
  public:
    LatLongGrid(int width, int height, LatLongPixels placement)
        : width_(width), height_(height), placement_(placement), uEdge_(latLongEdges(placement, width)),
          zEdge_(latLongEdges(placement, height)) {
        // Row edges as z = sin(latitude) = cos(pi v).
        for (double& z : zEdge_)
            z = std::cos(kPi * z);
        zEdge_.front() = 1.0;
        zEdge_.back() = -1.0;
        rowHeight_.resize(std::size_t(height));
        for (int r = 0; r < height; ++r)
            rowHeight_[std::size_t(r)] = zEdge(r) - zEdge(r + 1);
    }

    const std::vector<double>& uEdges() const { return uEdge_; }

    // Column holding u in [0, 1). The first guess only has to be near: the loops make it exact.
    int column(double u) const {
        const int w = width_;
        int c = latLongPixelAt(placement_, u, w);
        while (c > 0 && u < uEdge_[std::size_t(c)])
            --c;
        while (c < w - 1 && u >= uEdge_[std::size_t(c) + 1])
            ++c;
        return c;
    }

    // Rows crossed by the meridian arc [zLo, zHi] of a column and the z length in the first and last.
    struct RowSpan {
        int top, bottom;                // top <= bottom
        double topLength, bottomLength; // topLength is the whole arc's when top == bottom
    };
    RowSpan rowSpan(double zLo, double zHi) const {
        // An arc crosses a row or two (a texel is about as tall as a row at the resolution the ingest
        // picks): zLo's row is found from zHi's, without the second arccosine of row().
        const int top = row(zHi), bottom = rowBelow(zLo, top);
        if (top == bottom) return {top, bottom, zHi - zLo, 0.0};
        return {top, bottom, zHi - zEdge(top + 1), zEdge(bottom) - zLo};
    }

    int width() const { return width_; }
    int height() const { return height_; }
    // The row holding z (on a row edge, the row above it).
    int rowOf(double z) const { return row(z); }
    double rowHeight(int r) const { return rowHeight_[std::size_t(r)]; }

  private:
    double zEdge(int r) const { return zEdge_[std::size_t(r)]; }
    // Row r spans z in [zEdge(r + 1), zEdge(r)]. The first guess only has to be near: the loops make it
    // exact.
    int row(double z) const {
        const int h = height_;
        const double v = approximateAcos(std::clamp(z, -1.0, 1.0)) / kPi;
        int r = latLongPixelAt(placement_, v, h);
        while (r > 0 && z > zEdge(r))
            --r;
        while (r < h - 1 && z < zEdge(r + 1))
            ++r;
        return r;
    }

    // The row holding z, at or below row `top` (z <= zEdge(top)); on a row edge, the row above it.
    int rowBelow(double z, int top) const {
        const int h = height_;
        int r = top;
        while (r < h - 1 && z < zEdge(r + 1))
            ++r;
        return r;
    }

    int width_, height_;
    LatLongPixels placement_;
    std::vector<double> uEdge_, zEdge_;
    std::vector<double> rowHeight_; // zEdge(r) - zEdge(r + 1)
};

// Integral of column c of `image` (ImageRGBA, or ImageRGBE decoded to the same floats) over the rows of
// `span` (rows H-1-r when `mirrored`), per channel. RGBA even when alpha is not resampled: four doubles are
// two SIMD registers, where three are done one by one, and the RGB sums are the same.
template <class Image>
glm::dvec4 integrateColumn(const Image& image, const LatLongGrid& grid, int c,
                           const LatLongGrid::RowSpan& span, bool mirrored) {
    const int flip = mirrored ? grid.height() - 1 : 0, sign = mirrored ? -1 : 1;
    auto at = [&](int r) { return glm::dvec4(image.at(c, flip + sign * r)); };
    if (span.top == span.bottom) return at(span.top) * span.topLength;
    glm::dvec4 sum = at(span.top) * span.topLength;
    for (int r = span.top + 1; r < span.bottom; ++r)
        sum += at(r) * grid.rowHeight(r);
    return sum + at(span.bottom) * span.bottomLength;
}

// A texel that shares the geometry of the one computed: it integrates column (c + columnOffset) mod W, or
// (columnOffset - c) mod W when reflected, for the computed texel's column c, and row H-1-r for row r when
// mirrored.
struct TexelImage {
    int face, i, j;
    int columnOffset; // in [0, W)
    bool reflected;
    bool mirrored;

    int column(int c, int width) const {
        if (reflected) return c <= columnOffset ? columnOffset - c : columnOffset - c + width;
        return c + columnOffset < width ? c + columnOffset : c + columnOffset - width;
    }
};

// Up to 4 quarter turns of a texel and of its reflection, each with its mirror image.
constexpr int kMaxImages = 16;

struct Orbit {
    std::array<TexelImage, kMaxImages> images;
    int count = 0;
};

// Which symmetries of the cube and the lat-long grid the resampling may use (see the top of the file).
struct Symmetry {
    bool mirror = false;       // y -> -y: an even face size
    bool quarterTurns = false; // also a quarter turn about +Y: Centre placement, width a multiple of 4
    bool reflections = false;  // also a reflection in a vertical plane: quarter turns and no rotation

    Symmetry(int faceSize, int width, LatLongPixels placement, double rotateRadians, bool use)
        : mirror(use && faceSize % 2 == 0),
          quarterTurns(mirror && placement == LatLongPixels::Centre && width % 4 == 0),
          reflections(quarterTurns && rotateRadians == 0.0) {}

    // Whether texel (face, i, j) is the one of its orbit whose geometry is computed: with reflections, +Z's
    // upper left quadrant and the half i <= j of +Y's quadrant i, j < n/2; with quarter turns, +Z's upper
    // half and +Y's quadrant; with the mirror only, the side faces' upper halves and +Y.
    bool computes(int face, int i, int j, int n) const {
        const int half = n / 2;
        if (reflections) return (face == 4 && i < half && j < half) || (face == 2 && i <= j && j < half);
        if (quarterTurns) return (face == 4 && j < half) || (face == 2 && i < half && j < half);
        if (mirror) return face == 2 || (face != 3 && j < half);
        return true;
    }

    // The texels that take texel (face, i, j)'s geometry, itself first. A quarter turn about +Y (+Z toward
    // +X) takes +Z's texel (i, j) to +X's, -Z's, -X's (i, j) in turn (kernels/cube.h face directions),
    // +Y's (i, j) to (j, n-1-i), and adds pi/2 to the longitude: u falls by 1/4, W/4 columns. The mirror
    // takes a side face's (i, j) to (i, n-1-j) and +Y's (i, j) to -Y's (i, n-1-j). Without rotation the
    // seam u = 0 is at longitude pi, and u = 1/2 - phi / (2 pi): the reflection x -> -x takes +Z's (i, j) to
    // (n-1-i, j) and phi to -phi, u to 1 - u, column c to W-1-c; the reflection x <-> z takes +Y's (i, j) to
    // (j, i) and phi to pi/2 - phi, u to 3/4 - u, column c to 3W/4-1-c. A texel on +Y's diagonal is its own
    // reflection.
    Orbit orbit(int face, int i, int j, int n, int width) const {
        Orbit o;
        const int turns = quarterTurns ? 4 : 1;
        constexpr int kSideTurns[4] = {4, 0, 5, 1};
        auto addTurns = [&](TexelImage t) {
            const int firstOffset = t.columnOffset;
            for (int k = 0; k < turns; ++k) {
                o.images[std::size_t(o.count++)] = t;
                if (mirror) {
                    TexelImage m = t;
                    m.face = t.face == 2 ? 3 : t.face;
                    m.j = n - 1 - t.j;
                    m.mirrored = true;
                    o.images[std::size_t(o.count++)] = m;
                }
                t.face = t.face == 2 ? 2 : kSideTurns[(k + 1) % 4];
                t.columnOffset = (firstOffset + width - (k + 1) * (width / 4)) % width;
                if (face == 2) t = {2, t.j, n - 1 - t.i, t.columnOffset, t.reflected, false};
            }
        };
        addTurns({face, i, j, 0, false, false});
        if (reflections && !(face == 2 && i == j))
            addTurns(face == 2 ? TexelImage{2, j, i, 3 * width / 4 - 1, true, false}
                               : TexelImage{face, n - 1 - i, j, width - 1, true, false});
        return o;
    }
};

struct TexelIntegral {
    std::array<glm::dvec4, kMaxImages> energy{}; // per image of the orbit
    double area = 0.0;
};

// The longitudes of a texel's four corners (NaN for a corner at a pole, which has none), looked up in a
// per-face grid: neighbouring texels share corners, so atan2 runs once per corner, not four times per texel.
using CornerLongitudes = std::array<double, 4>;

// A quadrature node of a texel's longitude range: its meridian, weight and lat-long column.
struct MeridianNode {
    FaceMeridian meridian;
    double weight;
    int column;
};

// The quadrature nodes of a texel with these corner longitudes (`cuts` is scratch).
void texelNodes(const LatLongGrid& grid, const FaceFrame& frame, const Square& sq,
                const CornerLongitudes& corners, double rotate, std::vector<double>& cuts,
                std::vector<MeridianNode>& nodes) {
    // Longitude range of the texel: its corners' longitudes unwrapped around one of them (a texel that
    // holds no pole spans less than pi); a texel that holds a pole inside sees every longitude.
    cuts.clear();
    nodes.clear();
    double phiMin, phiMax;
    const bool holdsPole =
        std::fabs(frame.o.y) == 1.0 && sq.a0 < 0.0 && 0.0 < sq.a1 && sq.b0 < 0.0 && 0.0 < sq.b1;
    if (holdsPole) {
        phiMin = -kPi;
        phiMax = kPi;
        for (double phi : corners)
            cuts.push_back(phi);
    } else {
        double reference = std::numeric_limits<double>::quiet_NaN();
        phiMin = 1e300;
        phiMax = -1e300;
        for (double corner : corners) {
            if (std::isnan(corner)) continue;
            if (std::isnan(reference)) reference = corner;
            // remainder(corner - reference, 2 pi) for a difference within (-2 pi, 2 pi), without the call.
            double difference = corner - reference;
            if (difference > kPi) difference -= kTwoPi;
            if (difference < -kPi) difference += kTwoPi;
            const double phi = reference + difference;
            cuts.push_back(phi);
            phiMin = std::min(phiMin, phi);
            phiMax = std::max(phiMax, phi);
        }
    }
    // Source u of a target longitude, not wrapped: u = 0.5 - (phi - rotate) / (2 pi) (docs/conventions.md).
    auto uOf = [&](double phi) { return 0.5 - (phi - rotate) / kTwoPi; };
    auto phiOf = [&](double u) { return (0.5 - u) * kTwoPi + rotate; };
    // Pixel column edges inside the range, in every period of u it spans (the seam u = 0 is one of them).
    const double uLo = uOf(phiMax), uHi = uOf(phiMin);
    const std::vector<double>& edges = grid.uEdges();
    for (double period = std::floor(uLo); period <= uHi; period += 1.0) {
        const auto first = std::upper_bound(edges.begin(), edges.end() - 1, uLo - period);
        const auto last = std::lower_bound(edges.begin(), edges.end() - 1, uHi - period);
        for (auto it = first; it < last; ++it)
            cuts.push_back(phiOf(period + *it));
    }
    cuts.push_back(phiMin);
    cuts.push_back(phiMax);
    std::sort(cuts.begin(), cuts.end());

    for (std::size_t i = 0; i + 1 < cuts.size(); ++i) {
        const double p0 = std::max(cuts[i], phiMin), p1 = std::min(cuts[i + 1], phiMax);
        if (!(p1 - p0 > 1e-15)) continue;
        const double half = 0.5 * (p1 - p0), mid = 0.5 * (p0 + p1);
        const double u = uOf(mid);
        const int column = grid.column(u - std::floor(u));
        for (int k = 0; k < kOrder; ++k)
            nodes.push_back({faceMeridian(frame, mid + half * kNodes[k]), half * kWeights[k], column});
    }
}

template <class Image>
TexelIntegral integrateTexel(const Image& image, const LatLongGrid& grid, const FaceFrame& frame,
                             const Square& sq, const std::vector<MeridianNode>& nodes, const Orbit& orbit) {
    TexelIntegral sum;
    sum.energy.fill(glm::dvec4(0.0));
    for (const MeridianNode& node : nodes) {
        double zLo, zHi;
        if (!clipMeridian(frame, sq, node.meridian, zLo, zHi)) continue;
        const double w = node.weight;
        sum.area += w * (zHi - zLo);
        const LatLongGrid::RowSpan span = grid.rowSpan(zLo, zHi);
        for (int m = 0; m < orbit.count; ++m) {
            const TexelImage& texel = orbit.images[std::size_t(m)];
            sum.energy[std::size_t(m)] +=
                w *
                integrateColumn(image, grid, texel.column(node.column, grid.width()), span, texel.mirrored);
        }
    }
    return sum;
}

// The resampling of one lat-long size to one cube: the grid, the symmetry and the corner longitudes, shared
// by every texel; texels are computed from an image given to each call (the whole lat-long, or the rows that
// a streamed ingest holds, resampleLatLongBlocks).
class CubeResampler {
  public:
    CubeResampler(int width, int height, int faceSize, LatLongPixels placement, double rotateRadians,
                  bool withAlpha, bool useSymmetry)
        : grid_(checked(width, height, faceSize, placement), height, placement),
          symmetry_(faceSize, width, placement, rotateRadians, useSymmetry), cube_(faceSize),
          faceSize_(faceSize), rotate_(rotateRadians), withAlpha_(withAlpha), step_(2.0 / faceSize) {
        const int corners = faceSize + 1; // per face and axis
        // Corner longitudes of the texels whose cuts are computed (texel (i, j)'s corners (i..i+1, j..j+1)):
        // a side face's first two rows of corners (its columns' cuts are those of their first texel, below),
        // +-Y's up to the last computed texel (a quadrant with quarter turns). Only these: each is an atan2,
        // and memory first touched costs a page fault per 4 KB (read_image.cpp), so a table of every corner
        // of every face took 6x as much time and 10x as much memory.
        std::vector<std::array<int, 2>> cornerRows; // (face, j)
        std::size_t cornerCount = 0;
        for (int face = 0; face < 6; ++face) {
            if (!symmetry_.computes(face, 0, 0, faceSize)) continue;
            const bool pole = face == 2 || face == 3;
            const int extent = pole && symmetry_.quarterTurns ? faceSize / 2 + 1 : corners;
            CornerTable& table = cornerTable_[std::size_t(face)];
            table = {cornerCount, pole ? extent : std::min(2, corners), extent};
            cornerCount += std::size_t(table.rows) * std::size_t(table.columns);
            for (int j = 0; j < table.rows; ++j)
                cornerRows.push_back({face, j});
        }
        cornerLongitude_.resize(cornerCount);
        tbb::parallel_for(std::size_t(0), cornerRows.size(), [&](std::size_t k) {
            const auto [face, j] = cornerRows[k];
            const CornerTable& table = cornerTable_[std::size_t(face)];
            const FaceFrame frame = faceFrame(face);
            double* row = &cornerLongitude_[table.offset + std::size_t(j) * std::size_t(table.columns)];
            for (int i = 0; i < table.columns; ++i) {
                const glm::dvec3 d = frame.at(-1.0 + i * step_, -1.0 + j * step_);
                row[i] =
                    d.x * d.x + d.z * d.z < 1e-24 ? std::numeric_limits<double>::quiet_NaN() : longitude(d);
            }
        });
    }

    const LatLongGrid& grid() const { return grid_; }
    const Symmetry& symmetry() const { return symmetry_; }
    int faceSize() const { return faceSize_; }
    CubeMap takeCube() { return std::move(cube_); }

    // Texels (face, i, j) computed of a side face's column i: j < sideCount(face, i) (none when the column's
    // texels are all computed as images of others).
    int sideCount(int face, int i) const {
        int j = 0;
        while (j < faceSize_ && symmetry_.computes(face, i, j, faceSize_))
            ++j;
        return j;
    }
    // Texels (face, i, j) computed of +-Y's row j: i < poleCount(face, j).
    int poleCount(int face, int j) const {
        int i = 0;
        while (i < faceSize_ && symmetry_.computes(face, i, j, faceSize_))
            ++i;
        return i;
    }

    struct Scratch {
        std::vector<double> cuts;
        std::vector<MeridianNode> nodes;
    };

    // Texels (face, i, rowOf(k)) for k < count of a side face's column i. Side faces (+-X, +-Z) go column by
    // column: their vertical texel edges are meridians, so every texel of a face column has the same corner
    // longitudes (a corner's horizontal direction does not depend on its height), hence the same cuts and
    // quadrature meridians, computed once per column.
    template <class Image, class RowOf>
    void sideTexels(const Image& image, int face, int i, int count, RowOf rowOf, Scratch& scratch) {
        const FaceFrame frame = faceFrame(face);
        texelNodes(grid_, frame, square(i, 0), cornerLongitudes(face, i, 0), rotate_, scratch.cuts,
                   scratch.nodes);
        for (int k = 0; k < count; ++k)
            resampleTexel(image, face, frame, i, rowOf(k), scratch.nodes);
    }

    // Texel (face, i, j) of +-Y, with its own cuts.
    template <class Image>
    void poleTexel(const Image& image, int face, int i, int j, Scratch& scratch) {
        const FaceFrame frame = faceFrame(face);
        texelNodes(grid_, frame, square(i, j), cornerLongitudes(face, i, j), rotate_, scratch.cuts,
                   scratch.nodes);
        resampleTexel(image, face, frame, i, j, scratch.nodes);
    }

    // The lat-long rows texel (face, i, j) reads (its orbit's mirror images read rows H-1-r of these),
    // widened by two rows: those of the texel's extreme z = sin(latitude), which lie on its edges (a
    // great-circle arc's highest or lowest point is an end or the one interior point where z' = 0) unless it
    // holds a pole. The rows integrateTexel reads lie between them: the arcs it clips are inside the texel.
    std::array<int, 2> texelRows(int face, int i, int j) const {
        const FaceFrame frame = faceFrame(face);
        const Square sq = square(i, j);
        const std::array<glm::dvec3, 4> corner = {frame.at(sq.a0, sq.b0), frame.at(sq.a1, sq.b0),
                                                  frame.at(sq.a1, sq.b1), frame.at(sq.a0, sq.b1)};
        double zMin = 1.0, zMax = -1.0;
        auto take = [&](const glm::dvec3& d) {
            const double z = d.y / glm::length(d);
            zMin = std::min(zMin, z);
            zMax = std::max(zMax, z);
        };
        for (int k = 0; k < 4; ++k) {
            const glm::dvec3 p = corner[std::size_t(k)], edge = corner[std::size_t((k + 1) % 4)] - p;
            take(p);
            // z(t) = (p + t edge).y / |p + t edge| is stationary where t = (p.y q - edge.y |p|^2) /
            // (edge.y q - p.y |edge|^2), q = p . edge.
            const double q = glm::dot(p, edge);
            const double denominator = edge.y * q - p.y * glm::dot(edge, edge);
            if (std::fabs(denominator) < 1e-300) continue;
            const double t = (p.y * q - edge.y * glm::dot(p, p)) / denominator;
            if (t > 0.0 && t < 1.0) take(p + t * edge);
        }
        const bool holdsPole =
            std::fabs(frame.o.y) == 1.0 && sq.a0 < 0.0 && 0.0 < sq.a1 && sq.b0 < 0.0 && 0.0 < sq.b1;
        if (holdsPole) (frame.o.y > 0.0 ? zMax : zMin) = frame.o.y;
        const int last = grid_.height() - 1;
        return {std::max(0, grid_.rowOf(zMax) - 2), std::min(last, grid_.rowOf(zMin) + 2)};
    }

  private:
    struct CornerTable {
        std::size_t offset = 0;
        int rows = 0, columns = 0;
    };

    static int checked(int width, int height, int faceSize, LatLongPixels placement) {
        if (width <= 0 || height <= 0) throw Error("lat-long resampling: empty image");
        if (faceSize <= 0) throw Error("lat-long resampling: face size must be positive");
        if (placement == LatLongPixels::Auto)
            throw Error("lat-long resampling: internal: unresolved placement");
        return width;
    }

    Square square(int i, int j) const {
        return Square{-1.0 + i * step_, -1.0 + (i + 1) * step_, -1.0 + j * step_, -1.0 + (j + 1) * step_};
    }

    CornerLongitudes cornerLongitudes(int face, int i, int j) const {
        const CornerTable& table = cornerTable_[std::size_t(face)];
        const double* below = &cornerLongitude_[table.offset + std::size_t(j) * std::size_t(table.columns)];
        const double* above = below + table.columns;
        return CornerLongitudes{below[i], above[i], below[i + 1], above[i + 1]};
    }

    // Each computed texel writes its whole orbit; orbits do not overlap, so tasks never write the same texel,
    // and each texel's value comes from one fixed computation whatever the scheduling.
    template <class Image>
    void resampleTexel(const Image& image, int face, const FaceFrame& frame, int i, int j,
                       const std::vector<MeridianNode>& nodes) {
        const Orbit orbit = symmetry_.orbit(face, i, j, faceSize_, grid_.width());
        const TexelIntegral t = integrateTexel(image, grid_, frame, square(i, j), nodes, orbit);
        for (int m = 0; m < orbit.count; ++m) {
            const TexelImage& at = orbit.images[std::size_t(m)];
            const glm::dvec4 v = t.area > 0.0 ? t.energy[std::size_t(m)] / t.area : glm::dvec4(0.0);
            cube_.faces[std::size_t(at.face)].at(at.i, at.j) =
                glm::vec4(glm::vec3(glm::dvec3(v)), withAlpha_ ? resampledAlpha(v.w) : 1.0f);
        }
    }

    LatLongGrid grid_;
    Symmetry symmetry_;
    CubeMap cube_;
    int faceSize_;
    double rotate_;
    bool withAlpha_;
    double step_;
    std::array<CornerTable, 6> cornerTable_{};
    std::vector<double> cornerLongitude_;
};

constexpr std::array<int, 4> kSideFaces = {0, 1, 4, 5};

template <class Image>
CubeMap resampleLatLong(const Image& latlong, int faceSize, LatLongPixels placement, double rotateRadians,
                        bool withAlpha, bool useSymmetry) {
    CubeResampler resampler(latlong.width, latlong.height, faceSize, placement, rotateRadians, withAlpha,
                            useSymmetry);
    tbb::parallel_for(tbb::blocked_range<int>(0, 4 * faceSize), [&](const tbb::blocked_range<int>& columns) {
        CubeResampler::Scratch scratch;
        for (int fc = columns.begin(); fc != columns.end(); ++fc) {
            const int face = kSideFaces[std::size_t(fc / faceSize)], i = fc % faceSize;
            const int count = resampler.sideCount(face, i);
            if (count > 0)
                resampler.sideTexels(
                    latlong, face, i, count, [](int k) { return k; }, scratch);
        }
    });
    tbb::parallel_for(tbb::blocked_range<int>(0, 2 * faceSize), [&](const tbb::blocked_range<int>& rows) {
        CubeResampler::Scratch scratch;
        for (int fr = rows.begin(); fr != rows.end(); ++fr) {
            const int face = 2 + fr / faceSize, j = fr % faceSize;
            for (int i = 0, count = resampler.poleCount(face, j); i < count; ++i)
                resampler.poleTexel(latlong, face, i, j, scratch);
        }
    });
    return resampler.takeCube();
}

// The rows of a lat-long that a streamed resampling holds, by pointer (null for the rows not held).
class HeldRows {
  public:
    explicit HeldRows(int height) : rows_(std::size_t(height), nullptr) {}
    glm::vec4 at(int c, int r) const {
        const glm::vec4* row = rows_[std::size_t(r)];
        if (!row)
            throw std::logic_error("lat-long resampling: internal: row " + std::to_string(r) + " not held");
        return row[c];
    }
    void hold(int firstRow, int rowCount, int width, const glm::vec4* pixels) {
        for (int r = 0; r < rowCount; ++r)
            rows_[std::size_t(firstRow + r)] =
                pixels ? pixels + std::size_t(r) * std::size_t(width) : nullptr;
    }

  private:
    std::vector<const glm::vec4*> rows_;
};

// A computed texel of a streamed resampling.
struct BlockTexel {
    std::uint8_t face;
    std::uint16_t i, j;
};

} // namespace

CubeMap resampleLatLongBlocks(LatLongBlocks& blocks, int faceSize, LatLongPixels placement,
                              double rotateRadians, bool useSymmetry) {
    const int width = blocks.width(), height = blocks.height(), blockRows = blocks.blockRows();
    if (faceSize > 65536) throw Error("lat-long resampling: face size must be at most 65536");
    CubeResampler resampler(width, height, faceSize, placement, rotateRadians, false, useSymmetry);
    const int n = faceSize;
    // The computed texels in resampleLatLong's order (side columns, then +-Y rows) and the rows each reads.
    std::vector<std::size_t> firstOf(6 * std::size_t(n) + 1, 0); // per side column, then per +-Y row
    for (int k = 0; k < 6 * n; ++k) {
        const int count = k < 4 * n ? resampler.sideCount(kSideFaces[std::size_t(k / n)], k % n)
                                    : resampler.poleCount(2 + (k - 4 * n) / n, (k - 4 * n) % n);
        firstOf[std::size_t(k) + 1] = firstOf[std::size_t(k)] + std::size_t(count);
    }
    const std::size_t texelCount = firstOf.back();
    std::vector<BlockTexel> texels(texelCount);
    std::vector<std::array<int, 2>> rows(texelCount);
    tbb::parallel_for(0, 6 * n, [&](int k) {
        const bool side = k < 4 * n;
        const int face = side ? kSideFaces[std::size_t(k / n)] : 2 + (k - 4 * n) / n, line = k % n;
        for (std::size_t t = firstOf[std::size_t(k)]; t < firstOf[std::size_t(k) + 1]; ++t) {
            const int step = int(t - firstOf[std::size_t(k)]);
            const int i = side ? line : step, j = side ? step : line;
            texels[t] = {std::uint8_t(face), std::uint16_t(i), std::uint16_t(j)};
            rows[t] = resampler.texelRows(face, i, j);
        }
    });
    // Slab s: the texels whose last row is in block s, in the order above; the rows they read, top and
    // (through the mirror) bottom.
    const int blockCount = (height + blockRows - 1) / blockRows;
    std::vector<std::size_t> slabFirst(std::size_t(blockCount) + 1, 0);
    std::vector<std::array<int, 2>> slabRows(std::size_t(blockCount), {height, -1});
    for (std::size_t t = 0; t < texelCount; ++t) {
        const int s = rows[t][1] / blockRows;
        ++slabFirst[std::size_t(s) + 1];
        slabRows[std::size_t(s)] = {std::min(slabRows[std::size_t(s)][0], rows[t][0]),
                                    std::max(slabRows[std::size_t(s)][1], rows[t][1])};
    }
    for (int s = 0; s < blockCount; ++s)
        slabFirst[std::size_t(s) + 1] += slabFirst[std::size_t(s)];
    std::vector<BlockTexel> slabTexels(texelCount);
    {
        std::vector<std::size_t> next(slabFirst.begin(), slabFirst.end() - 1);
        for (std::size_t t = 0; t < texelCount; ++t)
            slabTexels[next[std::size_t(rows[t][1] / blockRows)]++] = texels[t];
    }
    texels = {};
    rows = {};
    // The blocks each slab reads, and the last slab that reads each block (released after it).
    const bool mirror = resampler.symmetry().mirror;
    auto slabBlocks = [&](int s, auto&& visit) {
        const auto [top, bottom] = slabRows[std::size_t(s)];
        for (int b = top / blockRows; b <= bottom / blockRows; ++b)
            visit(b);
        if (mirror)
            for (int b = (height - 1 - bottom) / blockRows; b <= (height - 1 - top) / blockRows; ++b)
                visit(b);
    };
    std::vector<int> lastSlab(std::size_t(blockCount), -1);
    for (int s = 0; s < blockCount; ++s)
        if (slabFirst[std::size_t(s)] < slabFirst[std::size_t(s) + 1])
            slabBlocks(s, [&](int b) { lastSlab[std::size_t(b)] = s; });

    HeldRows held(height);
    std::vector<bool> holding(std::size_t(blockCount), false);
    auto blockRowCount = [&](int b) { return std::min(height, (b + 1) * blockRows) - b * blockRows; };
    struct Run {
        std::size_t begin, end; // slabTexels of one side column or one +-Y row
    };
    std::vector<Run> runs;
    // A slab's blocks not yet held are acquired (decoded) while the slab before it is resampled: the
    // decoder's own threads (OpenEXR's) take the time the resampling leaves idle, and the other way round.
    auto acquireBlocks = [&](int s) {
        slabBlocks(s, [&](int b) {
            if (holding[std::size_t(b)]) return;
            held.hold(b * blockRows, blockRowCount(b), width, blocks.acquire(b));
            holding[std::size_t(b)] = true;
        });
    };
    auto nextSlab = [&](int s) {
        while (s < blockCount && slabFirst[std::size_t(s)] == slabFirst[std::size_t(s) + 1])
            ++s;
        return s;
    };
    int next = nextSlab(0);
    if (next < blockCount) acquireBlocks(next);
    while (next < blockCount) {
        const int s = next;
        next = nextSlab(s + 1);
        const std::size_t first = slabFirst[std::size_t(s)], last = slabFirst[std::size_t(s) + 1];
        runs.clear();
        for (std::size_t t = first; t < last; ++t) {
            const BlockTexel& a = slabTexels[t];
            const bool side = a.face != 2 && a.face != 3;
            if (t > first) {
                const BlockTexel& b = slabTexels[t - 1];
                if (b.face == a.face && (side ? b.i == a.i : b.j == a.j)) {
                    runs.back().end = t + 1;
                    continue;
                }
            }
            runs.push_back({t, t + 1});
        }
        tbb::task_group prefetch;
        if (next < blockCount) prefetch.run([&, next] { acquireBlocks(next); });
        try {
            tbb::parallel_for(tbb::blocked_range<std::size_t>(0, runs.size()),
                              [&](const tbb::blocked_range<std::size_t>& range) {
                                  CubeResampler::Scratch scratch;
                                  for (std::size_t r = range.begin(); r != range.end(); ++r) {
                                      const std::span<const BlockTexel> run(&slabTexels[runs[r].begin],
                                                                            runs[r].end - runs[r].begin);
                                      const int face = run.front().face;
                                      if (face == 2 || face == 3) {
                                          for (const BlockTexel& t : run)
                                              resampler.poleTexel(held, face, t.i, t.j, scratch);
                                      } else {
                                          resampler.sideTexels(
                                              held, face, run.front().i, int(run.size()),
                                              [&](int k) { return int(run[std::size_t(k)].j); }, scratch);
                                      }
                                  }
                              });
        } catch (...) {
            try {
                prefetch.wait();
            } catch (...) { // the resampling's own error is the one to report
            }
            throw;
        }
        prefetch.wait();
        for (int b = 0; b < blockCount; ++b)
            if (holding[std::size_t(b)] && lastSlab[std::size_t(b)] == s) {
                held.hold(b * blockRows, blockRowCount(b), width, nullptr);
                blocks.release(b);
                holding[std::size_t(b)] = false;
            }
    }
    return resampler.takeCube();
}

float resampledAlpha(double alpha) {
    constexpr double kSnap = 1e-6;
    if (!(alpha > kSnap)) return 0.0f; // NaN cannot come from repaired pixels, but is transparent too
    return alpha >= 1.0 - kSnap ? 1.0f : float(alpha);
}

CubeMap resampleLatLongToCubeRotated(const ImageRGBA& latlong, int faceSize, LatLongPixels placement,
                                     double rotateRadians, bool withAlpha, bool useSymmetry) {
    return resampleLatLong(latlong, faceSize, placement, rotateRadians, withAlpha, useSymmetry);
}

CubeMap resampleLatLongToCubeRotated(const ImageRGBE& latlong, int faceSize, LatLongPixels placement,
                                     double rotateRadians, bool useSymmetry) {
    return resampleLatLong(latlong, faceSize, placement, rotateRadians, false, useSymmetry);
}

} // namespace ingest

CubeMap resampleLatLongToCube(const ImageRGBA& latlong, int faceSize, LatLongPixels placement) {
    return ingest::resampleLatLongToCubeRotated(latlong, faceSize, placement, 0.0);
}

} // namespace ibl
