// Runtime probe sampling: one work-item per shading point; the work-item lives in shade_points.h, the
// math in probe.h (shared with the C++ runtime's CPU path).
#include "shade_points.h"

__kernel void shadePoints(__global float* out, RuntimeParams params, __global const ShadingPoint* points,
                          __global const float* distantLd, __global const float* dfgLut,
                          __global const LocalProbe* probes, __global const float* localLd) {
    shadePointsItem(listWorkItem(params.pointCount), out, params, points, distantLd, dfgLut, probes, localLd);
}
