// OpenCL only: helpers for loops that put IBL_LANES consecutive iterations in the lanes of float8 vectors
// (ld_lanes.h, narrow_lobe_lanes.h). PoCL does not vectorize these loops across work-items (its
// optimization before the work-item loops packs pairs of scalar operations into <2 x float>, which the
// loop vectorizer then refuses), so the kernels vectorize them themselves.
#ifndef IBL_LANES_H
#define IBL_LANES_H

#include "portable.h"

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

#endif
