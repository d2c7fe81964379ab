// The work-item of runtime.cl: one shading point (iblbake/opencl/dispatch.h), shaded by probe.h's shadePoint.
// Output: 4 floats per point, RGB radiance (diffuse + specular) and the local probes' composed alpha.
#ifndef IBL_SHADE_POINTS_H
#define IBL_SHADE_POINTS_H

#include "probe.h"
#include "work_item.h"

IBL_BEGIN_NAMESPACE

IBL_FN void shadePointsItem(WorkItem t, IBL_GLOBAL float* out, RuntimeParams params,
                            IBL_GLOBAL const ShadingPoint* points, IBL_GLOBAL const float* distantLd,
                            IBL_GLOBAL const float* dfgLut, IBL_GLOBAL const LocalProbe* probes,
                            IBL_GLOBAL const float* localLd) {
    ShadeResult r = shadePoint(points[t.x], params, distantLd, dfgLut, probes, localLd);
    storeTexelAlpha(out, t, v3add(r.diffuse, r.specular), r.localAlpha);
}

IBL_END_NAMESPACE

#endif
