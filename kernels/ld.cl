// Specular LD: one work-item per output texel of one level; the work-items and the math live in ld.h.
#include "ld.h"

__kernel void ldLevel(__global float* out, LdParams params, __global const float* pyramid,
                      __global const float* table) {
    ldLevelItem(cubeWorkItem(params.faceSize), out, params, pyramid, table);
}

__kernel void ldBright(__global float* out, LdParams params, __global const float* clusters,
                       __global const float* bright) {
    ldBrightItem(cubeWorkItem(params.faceSize), out, params, clusters, bright);
}
