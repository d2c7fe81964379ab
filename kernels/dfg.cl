// DFG / diffuse LUT: one work-item per texel; the work-items and the math live in dfg.h.
#include "dfg.h"

__kernel void dfgLutChunk(__global float* out, DfgParams params, __global const float* table) {
    dfgChunkItem(imageWorkItem(params.size, params.size), out, params, table);
}

__kernel void addChunk(__global float* out, DfgParams params, __global const float* chunk) {
    dfgAddChunkItem(imageWorkItem(params.size, params.size), out, params, chunk);
}
