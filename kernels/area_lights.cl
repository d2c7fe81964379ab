// Area lights: one work-item per shading point; the work-item lives in area_light_points.h, the math in
// area_lights.h (shared with the C++ runtime's CPU path).
#include "area_light_points.h"

__kernel void shadeAreaLights(__global float* out, AreaLightParams params,
                              __global const ShadingPoint* points) {
    shadeAreaLightItem(listWorkItem(params.pointCount), out, params, points);
}
