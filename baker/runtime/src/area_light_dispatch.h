// What the area lights' and the textured lights' dispatches share (area_lights.cpp, light_card.cpp): the
// switches of kernels/area_lights.h that the options set, and one dispatch per term.
#pragma once

#include "iblbake/runtime/runtime.h"

#include <area_lights.h>

#include <cstddef>
#include <vector>

#include <glm/vec4.hpp>

namespace ibl {

inline uint32_t areaLightFlags(const RuntimeOptions& options) {
    uint32_t flags = 0;
    if (options.specular) flags |= IBL_RT_SPECULAR;
    if (options.diffuse) flags |= IBL_RT_DIFFUSE;
    if (options.diffuseModel == DiffuseModel::Disney) flags |= IBL_RT_DISNEY_DIFFUSE;
    if (options.f90FromF0) flags |= IBL_RT_F90_FROM_F0;
    return flags;
}

// `run(termFlags)` dispatches the kernel for one term (the options' flags with only IBL_RT_DIFFUSE or only
// IBL_RT_SPECULAR of the two) and returns its RGB per point: one dispatch per term, so that the 4-float
// output carries each on its own. Terms the options leave out stay zero.
template <class Run>
std::vector<AreaLightResult> shadeEachTerm(std::size_t pointCount, const RuntimeOptions& options, Run run) {
    const uint32_t flags = areaLightFlags(options);
    AreaLightResult zero;
    zero.diffuse = zero.specular = glm::vec3(0.0f);
    std::vector<AreaLightResult> out(pointCount, zero);
    for (uint32_t term : {uint32_t(IBL_RT_DIFFUSE), uint32_t(IBL_RT_SPECULAR)}) {
        if ((flags & term) == 0) continue;
        const std::vector<glm::vec4> radiance =
            run((flags & ~uint32_t(IBL_RT_DIFFUSE | IBL_RT_SPECULAR)) | term);
        for (std::size_t i = 0; i < pointCount; ++i)
            (term == IBL_RT_DIFFUSE ? out[i].diffuse : out[i].specular) = glm::vec3(radiance[i]);
    }
    return out;
}

} // namespace ibl
