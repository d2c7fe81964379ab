// Lat-long pixel placement (docs/conventions.md "Lat-long mapping and pixel placement"): where pixel (x, y)
// of a W x H lat-long sits in (u, v). The one definition every part of the baker that maps lat-long pixels to
// directions uses (the ingest's resampling, SphereTexels' lat-long cells, hence calibration, statistics and
// sun detection on lat-long pixels, and the tests' helpers).
//   - Centre: pixel (x, y) covers [x, x+1) x [y, y+1) of the W x H grid, centred at u = (x+0.5)/W,
//     v = (y+0.5)/H: how image tools, Blender, PTGui/Poly Haven and every peer's sampler read a lat-long.
//   - OpenExr: ImfEnvmap LatLongMap's own placement, centre u = x/(W-1), v = y/(H-1): the first and last
//     columns both on the 180-degree seam, the first and last rows on the poles; each pixel covers the
//     half-way points to its neighbours (edge k, 0 < k < n, at (k-0.5)/(n-1)), so seam columns and pole
//     rows are half cells. Files carrying OpenEXR's envmap = latlong attribute (OpenImageIO: textureformat
//     "LatLong Environment") were written this way.
#pragma once

#include <algorithm>
#include <cmath>
#include <string>

namespace ibl {

enum class LatLongPixels {
    Auto,   // a setting only: OpenExr for a file carrying the envmap attribute, else Centre
    Centre, // u = (x+0.5)/W
    OpenExr // u = x/(W-1)
};

// "auto", "centre" (also "center"), "openexr"; throws ibl::SettingError ("latLongPixels") otherwise.
LatLongPixels parseLatLongPixels(const std::string& name);
const char* latLongPixelsName(LatLongPixels placement); // "auto", "centre", "openexr"

// The placement a file is read with: `requested` unless Auto, else OpenExr when the file carries the
// envmap = latlong attribute (`envmapLatLong`), else Centre.
inline LatLongPixels resolveLatLongPixels(LatLongPixels requested, bool envmapLatLong) {
    if (requested != LatLongPixels::Auto) return requested;
    return envmapLatLong ? LatLongPixels::OpenExr : LatLongPixels::Centre;
}

// Coordinate (u of a column, v of a row, in [0, 1]) of edge k (0 <= k <= n) of n pixels: pixel i spans
// [latLongPixelEdge(i), latLongPixelEdge(i + 1)]. `placement` must be resolved (Auto reads as Centre).
inline double latLongPixelEdge(LatLongPixels placement, int k, int n) {
    if (k <= 0) return 0.0;
    if (k >= n) return 1.0;
    return placement == LatLongPixels::OpenExr ? (k - 0.5) / (n - 1) : double(k) / n;
}

// Coordinate of the centre of pixel i of n (the point the placement puts the pixel's value at).
inline double latLongPixelCentre(LatLongPixels placement, int i, int n) {
    if (placement == LatLongPixels::OpenExr) return n > 1 ? double(i) / (n - 1) : 0.5;
    return (i + 0.5) / n;
}

// The pixel (of n) holding coordinate c in [0, 1] (c on an edge: the pixel that starts there).
inline int latLongPixelAt(LatLongPixels placement, double c, int n) {
    const double i = placement == LatLongPixels::OpenExr ? std::floor(c * (n - 1) + 0.5) : std::floor(c * n);
    return std::clamp(int(i), 0, n - 1);
}

} // namespace ibl
