// Diffuse irradiance cube: one work-item per output texel; the work-items and the math live in
// irradiance.h.
#include "irradiance.h"

__kernel void irradianceSampled(__global float* out, IrradianceParams params, __global const float* pyramid,
                                __global const float* table) {
    irradianceSampledItem(cubeWorkItem(params.faceSize), out, params, pyramid, table);
}

__kernel void irradianceBright(__global float* out, IrradianceParams params, __global const float* bright) {
    irradianceBrightItem(cubeWorkItem(params.faceSize), out, params, bright);
}
