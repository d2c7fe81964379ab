// Specular LD: one work-item per output texel of one level; the math lives in ld.h.
#include "ld.h"

__kernel void ldLevel(LdParams params, __global const float* pyramid, __global const float* table,
                      __global const float* bright, __global float* out) {
    // Global range: (faceSize rounded up, faceSize, 6). No early return (see dfg.cl).
    uint n = params.faceSize;
    uint x = min((uint)get_global_id(0), n - 1u), y = get_global_id(1), face = get_global_id(2);
    vec3 d =
        v3normalize(cubeFaceDirection((int)face, ((float)x + 0.5f) / (float)n, ((float)y + 0.5f) / (float)n));
    vec3 c = v3add(integrateLd(d, pyramid, params.source, table, params.sampleCount, params.invWeightSum),
                   brightTexelsLd(d, bright, params.brightCount, params.alpha, params.invLobeIntegral,
                                  params.source.baseFaceSize));
    if (get_global_id(0) < n) {
        uint o = 4u * ((face * n + y) * n + x);
        out[o] = c.x;
        out[o + 1] = c.y;
        out[o + 2] = c.z;
        out[o + 3] = 1.0f;
    }
}
