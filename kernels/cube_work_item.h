// OpenCL-only helpers for kernels with one work-item per texel of a cube level. Global range:
// (faceSize rounded up to the group width, faceSize, 6). There is no early return: loops stay uniform
// across the work-group (see dfg.cl); items past the face's width compute a clamped texel and skip
// the store.
#ifndef IBL_CUBE_WORK_ITEM_H
#define IBL_CUBE_WORK_ITEM_H

#include "cube.h"

typedef struct {
    uint x, y, face, n;
    uint offset; // first float of the texel in an RGBA float output of the level
    int inRange; // this item owns a texel (not padding)
    vec3 direction;
} CubeWorkItem;

static inline CubeWorkItem cubeWorkItem(uint n) {
    CubeWorkItem t;
    t.n = n;
    t.x = min((uint)get_global_id(0), n - 1u);
    t.y = get_global_id(1);
    t.face = get_global_id(2);
    t.offset = 4u * ((t.face * n + t.y) * n + t.x);
    t.inRange = get_global_id(0) < n;
    t.direction = cubeTexelDirection((int)t.face, t.x, t.y, n);
    return t;
}

static inline void storeTexel(__global float* out, CubeWorkItem t, vec3 c) {
    if (!t.inRange) return;
    out[t.offset] = c.x;
    out[t.offset + 1] = c.y;
    out[t.offset + 2] = c.z;
    out[t.offset + 3] = 1.0f;
}

static inline void addToTexel(__global float* out, CubeWorkItem t, vec3 c) {
    if (!t.inRange) return;
    out[t.offset] += c.x;
    out[t.offset + 1] += c.y;
    out[t.offset + 2] += c.z;
}

#endif
