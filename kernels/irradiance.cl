// Diffuse irradiance cube: one work-item per output texel; the math lives in irradiance.h. Two
// kernels, as for LD (ld.cl): irradianceSampled writes the filtered-importance-sampled part in a loop
// simple and uniform enough for PoCL to vectorize across work-items, irradianceBright adds the bright
// texels integrated exactly.
#include "cube_work_item.h"
#include "irradiance.h"

__kernel void irradianceSampled(IrradianceParams params, __global const float* pyramid,
                                __global const float* table, __global float* out) {
    CubeWorkItem t = cubeWorkItem(params.faceSize);
    storeTexel(out, t,
               integrateIrradiance(t.direction, pyramid, params.source, table, params.sampleCount,
                                   params.invSampleCount));
}

__kernel void irradianceBright(IrradianceParams params, __global const float* bright, __global float* out) {
    CubeWorkItem t = cubeWorkItem(params.faceSize);
    addToTexel(out, t, brightTexelsIrradiance(t.direction, bright, params.brightCount));
}
