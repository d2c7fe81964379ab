// Specular LD: one work-item per output texel of one level; the math lives in ld.h. Two kernels, so
// that the filtered-importance-sampling loop stays uniform and simple enough for PoCL to vectorize:
// ldLevel writes the sampled part, ldBright adds the exactly integrated bright texels.
#include "ld.h"

// Global range of both: (faceSize rounded up to the group width, faceSize, 6). No early return (see dfg.cl).
__kernel void ldLevel(LdParams params, __global const float* pyramid, __global const float* table,
                      __global float* out) {
    uint n = params.faceSize;
    uint x = min((uint)get_global_id(0), n - 1u), y = get_global_id(1), face = get_global_id(2);
    vec3 d = cubeTexelDirection((int)face, x, y, n);
    vec3 c = integrateLd(d, pyramid, params.source, table, params.sampleCount, params.invWeightSum);
    if (get_global_id(0) < n) {
        uint o = 4u * ((face * n + y) * n + x);
        out[o] = c.x;
        out[o + 1] = c.y;
        out[o + 2] = c.z;
        out[o + 3] = 1.0f;
    }
}

__kernel void ldBright(LdParams params, __global const float* clusters, __global const float* bright,
                       __global float* out) {
    uint n = params.faceSize;
    uint x = min((uint)get_global_id(0), n - 1u), y = get_global_id(1), face = get_global_id(2);
    uint o = 4u * ((face * n + y) * n + x);
    vec3 d = cubeTexelDirection((int)face, x, y, n);
    float skipBelow = brightSkipThreshold(v3(out[o], out[o + 1], out[o + 2]), params.brightCount);
    vec3 c = brightTexelsLd(d, clusters, params.brightCount, bright, params.alpha, params.invLobeIntegral,
                            params.source.baseFaceSize, skipBelow);
    if (get_global_id(0) < n) {
        out[o] += c.x;
        out[o + 1] += c.y;
        out[o + 2] += c.z;
    }
}
