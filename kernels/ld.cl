// Specular LD: one work-item per output texel of one level; the math lives in ld.h. Two kernels, so
// that the filtered-importance-sampling loop stays uniform and simple enough for PoCL to vectorize:
// ldLevel writes the sampled part, ldBright adds the exactly integrated bright texels.
#include "cube_work_item.h"
#include "ld.h"

__kernel void ldLevel(LdParams params, __global const float* pyramid, __global const float* table,
                      __global float* out) {
    CubeWorkItem t = cubeWorkItem(params.faceSize);
    storeTexel(
        out, t,
        integrateLd(t.direction, pyramid, params.source, table, params.sampleCount, params.invWeightSum));
}

__kernel void ldBright(LdParams params, __global const float* clusters, __global const float* bright,
                       __global float* out) {
    CubeWorkItem t = cubeWorkItem(params.faceSize);
    float skipBelow =
        brightSkipThreshold(v3(out[t.offset], out[t.offset + 1], out[t.offset + 2]), params.brightCount);
    addToTexel(out, t,
               brightTexelsLd(t.direction, clusters, params.brightCount, bright, params.alpha,
                              params.invLobeIntegral, params.source.baseFaceSize, skipBelow));
}
