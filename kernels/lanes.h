// Helpers for loops that put IBL_LANES consecutive iterations in the lanes of float8 vectors (ld_lanes.h,
// narrow_lobe_lanes.h, footprint_lanes.h). PoCL does not vectorize these loops across work-items (its
// optimization before the work-item loops packs pairs of scalar operations into <2 x float>, which the
// loop vectorizer then refuses), so the kernels vectorize them themselves; the CPU backend compiles the same
// code with OpenCL's vector types from vector8.h.
#ifndef IBL_LANES_H
#define IBL_LANES_H

#include "cube.h"
#ifndef __OPENCL_VERSION__
#include "vector8.h"
#endif

IBL_BEGIN_NAMESPACE

#define IBL_LANES 8u

// The lanes' sum, pairwise.
#ifdef __OPENCL_VERSION__
static inline float sumLanes(float8 v) {
    float4 pairs = v.lo + v.hi;
    return (pairs.x + pairs.y) + (pairs.z + pairs.w);
}

// The largest lane.
static inline int maxLane(int8 v) {
    int4 pairs = max(v.lo, v.hi);
    return max(max(pairs.s0, pairs.s1), max(pairs.s2, pairs.s3));
}

// The lane numbers 0 .. 7.
static inline int8 laneIndices(void) {
    return (int8)(0, 1, 2, 3, 4, 5, 6, 7);
}
#else
inline float sumLanes(float8 v) {
    float pairs[4];
    for (int i = 0; i < 4; ++i)
        pairs[i] = v.v[i] + v.v[i + 4];
    return (pairs[0] + pairs[1]) + (pairs[2] + pairs[3]);
}

inline int maxLane(int8 v) {
    int largest = v.v[0];
    for (int i = 1; i < 8; ++i)
        largest = v.v[i] > largest ? v.v[i] : largest;
    return largest;
}

inline int8 laneIndices() {
    return int8(IntLanes{0, 1, 2, 3, 4, 5, 6, 7});
}

#endif

// cubeFaceDirection(face, s, t) of one face in every lane.
IBL_FN void cubeFaceDirectionLanes(int face, float8 s, float8 t, float8* x, float8* y, float8* z) {
    float8 sc = 2.0f * s - 1.0f, tc = 2.0f * t - 1.0f, one = 1.0f;
    switch (face) {
    case 0:
        *x = one, *y = -tc, *z = -sc;
        break;
    case 1:
        *x = -one, *y = -tc, *z = sc;
        break;
    case 2:
        *x = sc, *y = one, *z = tc;
        break;
    case 3:
        *x = sc, *y = -one, *z = -tc;
        break;
    case 4:
        *x = sc, *y = -tc, *z = one;
        break;
    default:
        *x = -sc, *y = -tc, *z = -one;
        break;
    }
}

// cubePatchSolidAngle in every lane.
IBL_FN float8 cubePatchSolidAngleLanes(float8 u0, float8 v0, float8 step) {
    float8 u = u0 + 0.5f * step, v = v0 + 0.5f * step;
    float8 r2 = 1.0f + u * u + v * v;
    float8 midpoint = step * step / (r2 * sqrt(r2));
    int8 exact = isgreaterequal(step, 0.03125f);
    if (!any(exact)) return midpoint;
    float8 u1 = u0 + step, v1 = v0 + step;
    float8 area =
        fabs(atan2(u0 * v0, sqrt(u0 * u0 + v0 * v0 + 1.0f)) - atan2(u0 * v1, sqrt(u0 * u0 + v1 * v1 + 1.0f)) -
             atan2(u1 * v0, sqrt(u1 * u1 + v0 * v0 + 1.0f)) + atan2(u1 * v1, sqrt(u1 * u1 + v1 * v1 + 1.0f)));
    return select(midpoint, area, exact);
}

// Patches first .. first + 7 of an S x S grid of step `step` from (u0, v0) on `face` (row-major): their
// corners (pu, pv), the unit directions through their centres, their solid angles and which lanes lie in
// the grid (lanes past its S * S patches repeat its pattern; their sums are the caller's to mask).
typedef struct {
    float8 pu, pv;
    float8 nx, ny, nz;
    float8 solidAngle;
    int8 inGrid;
} PatchLanes;

IBL_FN PatchLanes patchLanes(int face, float u0, float v0, float step, int S, int first) {
    int8 patch = first + laneIndices();
    PatchLanes p;
    p.pu = u0 + convert_float8(patch % S) * step;
    p.pv = v0 + convert_float8(patch / S) * step;
    float8 dx, dy, dz;
    cubeFaceDirectionLanes(face, 0.5f * (p.pu + 0.5f * step + 1.0f), 0.5f * (p.pv + 0.5f * step + 1.0f), &dx,
                           &dy, &dz);
    float8 inv = 1.0f / sqrt(dx * dx + dy * dy + dz * dz);
    p.nx = dx * inv, p.ny = dy * inv, p.nz = dz * inv;
    p.solidAngle = cubePatchSolidAngleLanes(p.pu, p.pv, (float8)step);
    p.inGrid = patch < S * S;
    return p;
}

IBL_END_NAMESPACE

#endif
