// Runtime probe sampling: one work-item per shading point; the math lives in probe.h (shared with the
// C++ runtime's CPU path). Output: 4 floats per point, RGB radiance (diffuse + specular) and the local
// probes' composed alpha.
#include "probe.h"

// Global range: pointCount rounded up to the group width. No early return (see dfg.cl).
__kernel void shadePoints(RuntimeParams params, __global const ShadingPoint* points,
                          __global const float* distantLd, __global const float* dfgLut,
                          __global const LocalProbe* probes, __global const float* localLd,
                          __global float* out) {
    uint count = params.pointCount;
    uint i = min((uint)get_global_id(0), count - 1u);
    ShadeResult r = shadePoint(points[i], params, distantLd, dfgLut, probes, localLd);
    if (get_global_id(0) < count) {
        out[4u * i] = r.diffuse.x + r.specular.x;
        out[4u * i + 1u] = r.diffuse.y + r.specular.y;
        out[4u * i + 2u] = r.diffuse.z + r.specular.z;
        out[4u * i + 3u] = r.localAlpha;
    }
}
