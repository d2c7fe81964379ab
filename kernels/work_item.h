// One work-item of a dispatch grid (baker/include/opencl/iblbake/opencl/dispatch.h): a texel of a cube level,
// a texel of an image or one element of a list, each owning the 4 floats at `offset` of its output. The
// OpenCL entry points get theirs from the global id (cubeWorkItem, imageWorkItem, listWorkItem); the CPU
// backend builds the same item for each element with the *At functions and calls the same item function.
//
// Global ranges are padded to whole work-groups along x and there is no early return: loops stay
// uniform across the work-group (see portable.h); an item past the grid's width computes a clamped
// element (inRange = 0) and its stores do nothing.
#ifndef IBL_WORK_ITEM_H
#define IBL_WORK_ITEM_H

#include "cube.h"

IBL_BEGIN_NAMESPACE

// Every output holds 4 floats per element (RGBA texels; RGB + alpha for shaded points).
#define IBL_OUTPUT_FLOATS 4u

typedef struct {
    uint x, y, face; // the element (clamped into the grid); y and face are 0 for a list
    uint offset;     // its first float in the output
    int inRange;     // this item owns an element (is not padding)
} WorkItem;

// Texel (x, y) of face `face` of a cube level of n x n faces; x is the padded global x.
IBL_FN WorkItem cubeWorkItemAt(uint x, uint y, uint face, uint n) {
    WorkItem t;
    t.x = min(x, n - 1u);
    t.y = y;
    t.face = face;
    t.offset = IBL_OUTPUT_FLOATS * ((face * n + y) * n + t.x);
    t.inRange = x < n;
    return t;
}

// Unit direction through the centre of a cube work-item's texel.
IBL_FN vec3 cubeWorkItemDirection(WorkItem t, uint n) {
    return cubeTexelDirection((int)t.face, t.x, t.y, n);
}

// Texel (x, y) of a width x height image; x and y may be padded.
IBL_FN WorkItem imageWorkItemAt(uint x, uint y, uint width, uint height) {
    WorkItem t;
    t.x = min(x, width - 1u);
    t.y = min(y, height - 1u);
    t.face = 0u;
    t.offset = IBL_OUTPUT_FLOATS * (t.y * width + t.x);
    t.inRange = x < width && y < height;
    return t;
}

// Element i of a list of `count`; i may be padded.
IBL_FN WorkItem listWorkItemAt(uint i, uint count) {
    WorkItem t;
    t.x = min(i, count - 1u);
    t.y = 0u;
    t.face = 0u;
    t.offset = IBL_OUTPUT_FLOATS * t.x;
    t.inRange = i < count;
    return t;
}

#ifdef __OPENCL_VERSION__
// Global range (faceSize padded to the group width, faceSize, 6).
static inline WorkItem cubeWorkItem(uint n) {
    return cubeWorkItemAt((uint)get_global_id(0), (uint)get_global_id(1), (uint)get_global_id(2), n);
}
// Global range (width padded to the group width, height).
static inline WorkItem imageWorkItem(uint width, uint height) {
    return imageWorkItemAt((uint)get_global_id(0), (uint)get_global_id(1), width, height);
}
// Global range (count padded to the group width).
static inline WorkItem listWorkItem(uint count) {
    return listWorkItemAt((uint)get_global_id(0), count);
}
#endif

IBL_FN vec3 loadTexel(IBL_GLOBAL const float* out, WorkItem t) {
    return v3(out[t.offset], out[t.offset + 1u], out[t.offset + 2u]);
}

// RGB and alpha 1.
IBL_FN void storeTexel(IBL_GLOBAL float* out, WorkItem t, vec3 c) {
    if (!t.inRange) return;
    out[t.offset] = c.x;
    out[t.offset + 1u] = c.y;
    out[t.offset + 2u] = c.z;
    out[t.offset + 3u] = 1.0f;
}

IBL_FN void storeTexelAlpha(IBL_GLOBAL float* out, WorkItem t, vec3 c, float alpha) {
    if (!t.inRange) return;
    out[t.offset] = c.x;
    out[t.offset + 1u] = c.y;
    out[t.offset + 2u] = c.z;
    out[t.offset + 3u] = alpha;
}

// Adds to the RGB the item's own texel holds (written by an earlier dispatch; alpha unchanged).
IBL_FN void addToTexel(IBL_GLOBAL float* out, WorkItem t, vec3 c) {
    if (!t.inRange) return;
    out[t.offset] += c.x;
    out[t.offset + 1u] += c.y;
    out[t.offset + 2u] += c.z;
}

IBL_END_NAMESPACE

#endif
