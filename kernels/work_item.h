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

IBL_FN uint greatestCommonDivisor(uint a, uint b) {
    while (b != 0u) {
        uint r = a % b;
        a = b;
        b = r;
    }
    return a;
}

// The row (face * n + y) that global row g of a cube level of n-texel faces computes in a strided order:
// (g s) mod 6n, s the first integer from 6n / golden ratio that is coprime to 6n, so a permutation of the
// rows in which neighbouring global rows are far apart. For kernels whose work gathers in a few rows (the
// bright pass: the texels near a sun): PoCL deals a kernel's work-groups to its threads in runs of up to
// 512 consecutive groups (its pthread scheduler's chunks), half a 128-px face, so in row order one thread
// got every texel near the sun (the 1k sample's 128-px bright pass: 16.7 -> 11.8 ms on 2 threads).
IBL_FN uint cubeStridedRow(uint g, uint n) {
    uint rows = 6u * n;
    uint stride = max((uint)(0.618034f * (float)rows), 1u);
    while (greatestCommonDivisor(stride, rows) != 1u)
        ++stride;
    return (g * stride) % rows; // g s < 2^32 for faces up to 8192 texels
}

#ifdef __OPENCL_VERSION__
// Global range (faceSize padded to the group width, faceSize, 6).
static inline WorkItem cubeWorkItem(uint n) {
    return cubeWorkItemAt((uint)get_global_id(0), (uint)get_global_id(1), (uint)get_global_id(2), n);
}
// cubeWorkItem with the level's rows in a strided order (cubeStridedRow), for kernels whose work gathers in a
// few rows.
static inline WorkItem cubeWorkItemStrided(uint n) {
    uint row = cubeStridedRow((uint)get_global_id(2) * n + (uint)get_global_id(1), n);
    return cubeWorkItemAt((uint)get_global_id(0), row % n, row / n, n);
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
