// Specular LD: one work-item per output texel of one level; the work-items and the math live in ld.h.
// ldLevel runs ld_lanes.h's vector form of ldLevelItem (the CPU backend's item), a table block per step.
#include "ld_lanes.h"

__kernel void ldLevel(__global float* out, LdParams params, __global const float* pyramid,
                      __global const float* table) {
    ldLevelLanesItem(cubeWorkItem(params.faceSize), out, params, pyramid, table);
}

__kernel void ldBright(__global float* out, LdParams params, __global const float* clusters,
                       __global const float* bright) {
    ldBrightItem(cubeWorkItem(params.faceSize), out, params, clusters, bright);
}

// Both parts in one dispatch, for the smallest levels (ld.h's ldOnePassItem).
__kernel void ldOnePass(__global float* out, LdParams params, __global const float* pyramid,
                        __global const float* table, __global const float* clusters,
                        __global const float* bright) {
    ldOnePassLanesItem(cubeWorkItem(params.faceSize), out, params, pyramid, table, clusters, bright);
}
