// Cube-like inputs (strips, crosses, six files, OpenEXR cube maps) -> our cube, exact in area.
//
// Each input face becomes a grid of cells on the face plane of one of our faces, already turned into our
// orientation. Our texels and the source cells are then both axis-aligned rectangles on the same face
// plane, and the solid angle of a rectangle has a closed form (kernels/cube.h cubeAreaElement), so each
// texel gets the exact solid-angle average of the cells it overlaps: same-size grids copy, other sizes
// are box-filtered without losing or gaining energy.
#include "ingest_internal.h"

#include "iblbake/core/error.h"

#include <OpenEXR/ImfEnvmap.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

namespace ibl::ingest {

namespace {

std::vector<double> uniformEdges(int n) {
    std::vector<double> e(std::size_t(n) + 1);
    for (int k = 0; k <= n; ++k)
        e[std::size_t(k)] = -1.0 + 2.0 * k / n;
    e.front() = -1.0;
    e.back() = 1.0;
    return e;
}

// A square region of an image, optionally turned by 180 degrees, as a face in our orientation.
SourceFace regionFace(const ImageRGBA& image, int x0, int y0, int size, bool turn180, bool withAlpha) {
    SourceFace f;
    f.cols = f.rows = size;
    f.values.resize(std::size_t(size) * std::size_t(size));
    if (withAlpha) f.alpha.resize(f.values.size());
    for (int r = 0; r < size; ++r)
        for (int c = 0; c < size; ++c) {
            const int x = turn180 ? size - 1 - c : c, y = turn180 ? size - 1 - r : r;
            const std::size_t cell = std::size_t(r) * std::size_t(size) + std::size_t(c);
            f.values[cell] = glm::vec3(image.at(x0 + x, y0 + y));
            if (withAlpha) f.alpha[cell] = image.at(x0 + x, y0 + y).w;
        }
    f.edgesA = f.edgesB = uniformEdges(size);
    return f;
}

// Breakpoints of [lo, hi] against a sorted edge list, and the source index of each piece.
void overlaps(const std::vector<double>& edges, double lo, double hi, std::vector<double>& cuts,
              std::vector<int>& index) {
    cuts.assign(1, lo);
    index.clear();
    const int n = int(edges.size()) - 1;
    int k = int(std::upper_bound(edges.begin(), edges.end(), lo) - edges.begin()) - 1;
    k = std::clamp(k, 0, n - 1);
    for (; k < n; ++k) {
        const double end = std::min(hi, edges[std::size_t(k) + 1]);
        if (end > cuts.back()) {
            index.push_back(k);
            cuts.push_back(end);
        }
        if (edges[std::size_t(k) + 1] >= hi) break;
    }
}

} // namespace

SourceFaces facesFromLayout(const std::vector<RawImage>& images, EnvLayout layout, bool withAlpha) {
    SourceFaces faces;
    if (layout == EnvLayout::SixFiles) {
        if (images.size() != 6)
            throw Error("six-files layout needs 6 files, got " + std::to_string(images.size()));
        for (int f = 0; f < 6; ++f) {
            const ImageRGBA& im = images[std::size_t(f)].pixels;
            faces[std::size_t(f)] = regionFace(im, 0, 0, im.width, false, withAlpha);
        }
        return faces;
    }
    const ImageRGBA& im = images.at(0).pixels;
    // Cell (column, row) of each face in units of the face size, in +X, -X, +Y, -Y, +Z, -Z order.
    struct Place {
        int col, row;
        bool turn180;
    };
    std::array<Place, 6> place{};
    int size = 0;
    switch (layout) {
    case EnvLayout::HorizontalStrip:
        size = im.height;
        for (int f = 0; f < 6; ++f)
            place[std::size_t(f)] = {f, 0, false};
        break;
    case EnvLayout::VerticalStrip:
        size = im.width;
        for (int f = 0; f < 6; ++f)
            place[std::size_t(f)] = {0, f, false};
        break;
    case EnvLayout::HorizontalCross: // see ingest.h: row 1 = -X, +Z, +X, -Z; +Y above +Z, -Y below
        size = im.width / 4;
        place = {{{2, 1, false}, {0, 1, false}, {1, 0, false}, {1, 2, false}, {1, 1, false}, {3, 1, false}}};
        break;
    case EnvLayout::VerticalCross: // the same unfolding with -Z below -Y, turned by 180 degrees
        size = im.width / 3;
        place = {{{2, 1, false}, {0, 1, false}, {1, 0, false}, {1, 2, false}, {1, 1, false}, {1, 3, true}}};
        break;
    default:
        throw Error(images.at(0).file + ": layout " + layoutName(layout) + " is not a face layout");
    }
    for (int f = 0; f < 6; ++f) {
        const Place& p = place[std::size_t(f)];
        faces[std::size_t(f)] = regionFace(im, p.col * size, p.row * size, size, p.turn180, withAlpha);
    }
    return faces;
}

SourceFaces facesFromExrCube(const RawImage& image, bool withAlpha) {
    const ImageRGBA& im = image.pixels;
    // Pixel indices relative to the data window's corner: ImfEnvmap's dataWindowForFace() does the same.
    const IMATH_NAMESPACE::Box2i window(IMATH_NAMESPACE::V2i(0, 0),
                                        IMATH_NAMESPACE::V2i(im.width - 1, im.height - 1));
    const int m = Imf::CubeMap::sizeOfFace(window);
    if (m <= 0 || im.height != 6 * m)
        throw Error(image.file + ": not an OpenEXR cube map (faces must be 1:6)");

    // ImfEnvmap puts pixel centres at face-plane coordinates -1 + 2k / (m - 1), edge to edge; each pixel
    // covers the half-way points to its neighbours, clipped to the face (edge pixels are half cells).
    std::vector<double> edges(std::size_t(m) + 1);
    edges.front() = -1.0;
    edges.back() = 1.0;
    for (int k = 1; k < m; ++k)
        edges[std::size_t(k)] = -1.0 + (2.0 * k - 1.0) / (m - 1);

    SourceFaces faces;
    // Imf::CubeMapFace lists +X, -X, +Y, -Y, +Z, -Z: our order.
    for (int f = 0; f < 6; ++f) {
        const auto exrFace = Imf::CubeMapFace(f);
        const FaceFrame frame = faceFrame(f);
        SourceFace& out = faces[std::size_t(f)];
        out.cols = out.rows = m;
        out.values.assign(std::size_t(m) * std::size_t(m), glm::vec3(-1.0f));
        if (withAlpha) out.alpha.assign(out.values.size(), 0.0f);
        out.edgesA = out.edgesB = edges;
        std::vector<char> filled(out.values.size(), 0);
        for (int py = 0; py < m; ++py)
            for (int px = 0; px < m; ++px) {
                const IMATH_NAMESPACE::V2f pif{float(px), float(py)};
                const IMATH_NAMESPACE::V3f d = Imf::CubeMap::direction(exrFace, window, pif);
                const IMATH_NAMESPACE::V2f pos = Imf::CubeMap::pixelPosition(exrFace, window, pif);
                // Project the direction onto our face's plane to find the cell it is the centre of.
                const glm::dvec3 dir(d.x, d.y, d.z);
                const double major = glm::dot(dir, frame.o);
                if (!(major > 0.0))
                    throw Error(image.file + ": ImfEnvmap face order is not +X, -X, +Y, -Y, +Z, -Z");
                const double a = glm::dot(dir, frame.u) / major, b = glm::dot(dir, frame.v) / major;
                const int ia = m == 1 ? 0 : int(std::lround((a + 1.0) * 0.5 * (m - 1)));
                const int ib = m == 1 ? 0 : int(std::lround((b + 1.0) * 0.5 * (m - 1)));
                const int x = int(std::lround(pos.x)), y = int(std::lround(pos.y));
                if (ia < 0 || ia >= m || ib < 0 || ib >= m || x < 0 || x >= im.width || y < 0 ||
                    y >= im.height)
                    throw Error(image.file + ": ImfEnvmap cube-face mapping out of range");
                const std::size_t cell = std::size_t(ib) * std::size_t(m) + std::size_t(ia);
                out.values[cell] = glm::vec3(im.at(x, y));
                if (withAlpha) out.alpha[cell] = im.at(x, y).w;
                filled[cell] = 1;
            }
        if (std::find(filled.begin(), filled.end(), 0) != filled.end())
            throw Error(image.file + ": ImfEnvmap cube-face mapping is not one to one");
    }
    return faces;
}

int sourceFaceSizeOf(const SourceFaces& faces) {
    int size = 0;
    for (const SourceFace& f : faces)
        size = std::max({size, f.cols, f.rows});
    return size;
}

CubeMap resampleFacesToCube(const SourceFaces& faces, int faceSize) {
    if (faceSize <= 0) throw Error("cube resampling: face size must be positive");
    CubeMap cube(faceSize);
    const std::vector<double> target = uniformEdges(faceSize);
    tbb::parallel_for(tbb::blocked_range<int>(0, 6 * faceSize), [&](const tbb::blocked_range<int>& rows) {
        std::vector<double> xs, ys, e;
        std::vector<int> cols, rws;
        for (int fr = rows.begin(); fr != rows.end(); ++fr) {
            const int face = fr / faceSize, j = fr % faceSize;
            const SourceFace& src = faces[std::size_t(face)];
            overlaps(src.edgesB, target[std::size_t(j)], target[std::size_t(j) + 1], ys, rws);
            for (int i = 0; i < faceSize; ++i) {
                overlaps(src.edgesA, target[std::size_t(i)], target[std::size_t(i) + 1], xs, cols);
                // Area element at every breakpoint pair; cell solid angles are its 2x2 differences.
                const std::size_t nx = xs.size();
                e.resize(nx * ys.size());
                for (std::size_t y = 0; y < ys.size(); ++y)
                    for (std::size_t x = 0; x < nx; ++x)
                        e[y * nx + x] = cubeAreaElementF64(xs[x], ys[y]);
                glm::dvec3 energy(0.0);
                double area = 0.0, alphaEnergy = 0.0;
                for (std::size_t y = 0; y + 1 < ys.size(); ++y)
                    for (std::size_t x = 0; x + 1 < nx; ++x) {
                        const double omega =
                            e[y * nx + x] - e[(y + 1) * nx + x] - e[y * nx + x + 1] + e[(y + 1) * nx + x + 1];
                        const std::size_t cell =
                            std::size_t(rws[y]) * std::size_t(src.cols) + std::size_t(cols[x]);
                        energy += omega * glm::dvec3(src.values[cell]);
                        if (!src.alpha.empty()) alphaEnergy += omega * double(src.alpha[cell]);
                        area += omega;
                    }
                const glm::dvec3 value = area > 0.0 ? energy / area : glm::dvec3(0.0);
                const float alpha =
                    src.alpha.empty() ? 1.0f : resampledAlpha(area > 0.0 ? alphaEnergy / area : 0.0);
                cube.faces[std::size_t(face)].at(i, j) = glm::vec4(glm::vec3(value), alpha);
            }
        }
    });
    return cube;
}

} // namespace ibl::ingest
