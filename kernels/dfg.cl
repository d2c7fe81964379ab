// DFG / diffuse LUT: one work-item per texel; the math lives in dfg.h.
#include "dfg.h"

__kernel void dfgLut(DfgParams params, __global const float* table, __global float* lut) {
    // No early return: the sample loop must stay work-group uniform so that PoCL can vectorize
    // across work-items; out-of-range items compute a clamped texel and skip the store.
    uint x = min((uint)get_global_id(0), params.size - 1u);
    uint y = min((uint)get_global_id(1), params.size - 1u);
    vec3 dfg = integrateDfg(dfgTexelCenter(x, params.size), dfgTexelCenter(y, params.size), table,
                              params.sampleCount);
    if (get_global_id(0) < params.size && get_global_id(1) < params.size) {
        uint o = 4 * (y * params.size + x);
        lut[o] = dfg.x;
        lut[o + 1] = dfg.y;
        lut[o + 2] = dfg.z;
        lut[o + 3] = 1.0f;
    }
}
