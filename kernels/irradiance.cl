// Diffuse irradiance cube: one work-item per output texel; the math lives in irradiance.h. Two
// kernels, as for LD (ld.cl): irradianceSampled writes the filtered-importance-sampled part in a loop
// simple and uniform enough for PoCL to vectorize across work-items, irradianceBright adds the bright
// texels integrated exactly.
#include "irradiance.h"

// Global range of both: (faceSize rounded up to the group width, faceSize, 6). No early return: the
// loops stay uniform across the work-group (see dfg.cl); out-of-range items skip the store.
__kernel void irradianceSampled(IrradianceParams params, __global const float* pyramid,
                                __global const float* table, __global float* out) {
    uint n = params.faceSize;
    uint x = min((uint)get_global_id(0), n - 1u), y = get_global_id(1), face = get_global_id(2);
    vec3 d = cubeTexelDirection((int)face, x, y, n);
    vec3 c = integrateIrradiance(d, pyramid, params.source, table, params.sampleCount, params.invSampleCount);
    if (get_global_id(0) < n) {
        uint o = 4u * ((face * n + y) * n + x);
        out[o] = c.x;
        out[o + 1] = c.y;
        out[o + 2] = c.z;
        out[o + 3] = 1.0f;
    }
}

__kernel void irradianceBright(IrradianceParams params, __global const float* bright, __global float* out) {
    uint n = params.faceSize;
    uint x = min((uint)get_global_id(0), n - 1u), y = get_global_id(1), face = get_global_id(2);
    vec3 c = brightTexelsIrradiance(cubeTexelDirection((int)face, x, y, n), bright, params.brightCount);
    if (get_global_id(0) < n) {
        uint o = 4u * ((face * n + y) * n + x);
        out[o] += c.x;
        out[o + 1] += c.y;
        out[o + 2] += c.z;
    }
}
