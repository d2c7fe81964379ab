// OpenCL only: helpers for loops that put IBL_LANES consecutive iterations in the lanes of float8 vectors
// (ld_lanes.h, narrow_lobe_lanes.h). PoCL does not vectorize these loops across work-items (its
// optimization before the work-item loops packs pairs of scalar operations into <2 x float>, which the
// loop vectorizer then refuses), so the kernels vectorize them themselves.
#ifndef IBL_LANES_H
#define IBL_LANES_H

#include "cube.h"

#define IBL_LANES 8u

// Eight reads of a buffer at the lanes' indices.
static inline float8 readLanes(__global const float* buffer, uint8 index) {
    return (float8)(buffer[index.s0], buffer[index.s1], buffer[index.s2], buffer[index.s3], buffer[index.s4],
                    buffer[index.s5], buffer[index.s6], buffer[index.s7]);
}

// The lanes' sum, pairwise.
static inline float sumLanes(float8 v) {
    float4 pairs = v.lo + v.hi;
    return (pairs.x + pairs.y) + (pairs.z + pairs.w);
}

// cubeFaceDirection(face, s, t) of one face in every lane.
static inline void cubeFaceDirectionLanes(int face, float8 s, float8 t, float8* x, float8* y, float8* z) {
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

// Patches first .. first + 7 of an S x S grid of step `step` from (u0, v0) on `face` (row-major; lanes past
// the grid's S * S patches repeat its pattern and are the caller's to mask): their corners (pu, pv) and
// the unit directions through their centres.
typedef struct {
    float8 pu, pv;
    float8 nx, ny, nz;
} PatchLanes;

static inline PatchLanes patchLanes(int face, float u0, float v0, float step, int S, int8 patch) {
    PatchLanes p;
    p.pu = u0 + convert_float8(patch % S) * step;
    p.pv = v0 + convert_float8(patch / S) * step;
    float8 dx, dy, dz;
    cubeFaceDirectionLanes(face, 0.5f * (p.pu + 0.5f * step + 1.0f), 0.5f * (p.pv + 0.5f * step + 1.0f), &dx,
                           &dy, &dz);
    float8 inv = 1.0f / sqrt(dx * dx + dy * dy + dz * dz);
    p.nx = dx * inv, p.ny = dy * inv, p.nz = dz * inv;
    return p;
}

// cubePatchSolidAngle in every lane.
static inline float8 cubePatchSolidAngleLanes(float8 u0, float8 v0, float8 step) {
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

#endif
