// Textured rectangle lights: one work-item per shading point; the work-item lives in
// textured_light_points.h, the math in textured_light.h (shared with the C++ runtime's CPU path).
#include "textured_light_points.h"

__kernel void shadeTexturedLights(__global float* out, TexturedLightParams params,
                                  __global const ShadingPoint* points, __global const float* card) {
    shadeTexturedLightItem(listWorkItem(params.pointCount), out, params, points, card);
}
