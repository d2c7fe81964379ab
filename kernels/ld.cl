// Specular LD: one work-item per output texel of one level; the work-items and the math live in ld.h (the
// sample and patch loops in float8 lanes: ld_lanes.h, narrow_lobe_lanes.h, footprint_lanes.h).
#include "ld.h"

__kernel void ldLevel(__global float* out, LdParams params, __global const float* pyramid,
                      __global const float* table) {
    ldLevelItem(cubeWorkItem(params.faceSize), out, params, pyramid, table);
}

__kernel void ldBright(__global float* out, LdParams params, __global const float* clusters,
                       __global const float* bright, __global const float* brightLanes) {
    ldBrightItem(cubeWorkItemStrided(params.faceSize), out, params, clusters, bright, brightLanes);
}

// Both parts in one dispatch, for the smallest levels (ld.h's ldOnePassItem).
__kernel void ldOnePass(__global float* out, LdParams params, __global const float* pyramid,
                        __global const float* table, __global const float* clusters,
                        __global const float* bright, __global const float* brightLanes) {
    ldOnePassItem(cubeWorkItem(params.faceSize), out, params, pyramid, table, clusters, bright, brightLanes);
}
