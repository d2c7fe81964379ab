// DFG / diffuse LUT: one work-item per texel integrates one chunk of samples; a second kernel adds
// the chunk to the running sums. The math lives in dfg.h.
#include "dfg.h"

__kernel void dfgLutChunk(DfgParams params, __global const float* table, __global float* chunkSums) {
    // No early return: the sample loop must stay work-group uniform so that PoCL can vectorize
    // across work-items; out-of-range items compute a clamped texel and skip the store. The store is
    // a plain write: reading the output here (+=) stops PoCL from vectorizing the sample loop.
    uint x = min((uint)get_global_id(0), params.size - 1u);
    uint y = min((uint)get_global_id(1), params.size - 1u);
    vec3 chunk = integrateDfgChunk(dfgTexelCenter(x, params.size), dfgTexelCenter(y, params.size), table,
                                   params.firstSample, params.endSample);
    if (get_global_id(0) < params.size && get_global_id(1) < params.size) {
        uint o = 4 * (y * params.size + x);
        chunkSums[o] = chunk.x;
        chunkSums[o + 1] = chunk.y;
        chunkSums[o + 2] = chunk.z;
    }
}

__kernel void addChunk(__global const float4* chunkSums, __global float4* sums) {
    size_t i = get_global_id(0);
    sums[i] += chunkSums[i];
}
