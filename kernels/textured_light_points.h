// The work-item of textured_light.cl: one shading point lit by one textured rectangle light
// (kernels/textured_light.h). Output: 4 floats per point, the RGB radiance of the terms params.flags
// selects, and 0.
#ifndef IBL_TEXTURED_LIGHT_POINTS_H
#define IBL_TEXTURED_LIGHT_POINTS_H

#include "textured_light.h"
#include "work_item.h"

IBL_BEGIN_NAMESPACE

// The kernel's argument by value (4-byte members only: the same layout in C++ and OpenCL C).
IBL_STRUCT(TexturedLightParams) {
    AreaLight light;
    LightCardLayout card;
    uint32_t flags; // IBL_RT_DIFFUSE, IBL_RT_SPECULAR, IBL_RT_DISNEY_DIFFUSE, IBL_RT_F90_FROM_F0
    float dielectricF0;
    uint32_t pointCount;
};

IBL_FN void shadeTexturedLightItem(WorkItem t, IBL_GLOBAL float* out, TexturedLightParams params,
                                   IBL_GLOBAL const ShadingPoint* points, IBL_GLOBAL const float* card) {
    AreaLightResult r = texturedLightShade(
        params.light, params.card, card, areaSurfaceFromPoint(points[t.x], params.dielectricF0, params.flags),
        params.flags);
    storeTexelAlpha(out, t, v3add(r.diffuse, r.specular), 0.0f);
}

IBL_END_NAMESPACE

#endif
