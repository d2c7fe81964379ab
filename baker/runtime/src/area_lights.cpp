// Area lights on the CPU: kernels/area_lights.h over the points, and the lights' construction.
#include "iblbake/runtime/runtime_area_lights.h"

#include "point_dispatch.h"

#include <glm/geometric.hpp>

namespace ibl {

namespace {

AreaLight makeAreaLight(uint32_t shape, const glm::vec3& center, const glm::vec3& normal,
                        const glm::vec3& tangent, float halfWidth, float halfHeight, const glm::vec3& color,
                        float lumens) {
    AreaLight light{};
    light.position = center;
    light.shape = shape;
    light.normal = glm::normalize(normal);
    light.tangent = glm::normalize(tangent - light.normal * glm::dot(tangent, light.normal));
    light.halfWidth = halfWidth;
    light.halfHeight = halfHeight;
    light.color = color;
    light.luminance = areaLightLuminanceFromPower(shape, halfWidth, halfHeight, lumens);
    return light;
}

// Any unit vector perpendicular to n (for the shapes without a tangent).
glm::vec3 perpendicular(const glm::vec3& n) {
    return frameFromNormal(glm::normalize(n)).t;
}

// The switches of kernels/area_lights.h that the options set.
uint32_t areaLightFlags(const RuntimeOptions& options) {
    uint32_t flags = 0;
    if (options.specular) flags |= IBL_RT_SPECULAR;
    if (options.diffuse) flags |= IBL_RT_DIFFUSE;
    if (options.diffuseModel == DiffuseModel::Disney) flags |= IBL_RT_DISNEY_DIFFUSE;
    if (options.f90FromF0) flags |= IBL_RT_F90_FROM_F0;
    return flags;
}

} // namespace

AreaLight sphereAreaLight(const glm::vec3& center, float radius, const glm::vec3& color, float lumens) {
    return makeAreaLight(IBL_AREA_SPHERE, center, {0.0f, 0.0f, 1.0f}, {1.0f, 0.0f, 0.0f}, radius, radius,
                         color, lumens);
}

AreaLight diskAreaLight(const glm::vec3& center, const glm::vec3& normal, float radius,
                        const glm::vec3& color, float lumens) {
    return makeAreaLight(IBL_AREA_DISK, center, normal, perpendicular(normal), radius, radius, color, lumens);
}

AreaLight rectangleAreaLight(const glm::vec3& center, const glm::vec3& normal, const glm::vec3& tangent,
                             float width, float height, const glm::vec3& color, float lumens) {
    return makeAreaLight(IBL_AREA_RECTANGLE, center, normal, tangent, 0.5f * width, 0.5f * height, color,
                         lumens);
}

std::vector<AreaLightResult> shadeAreaLightCpu(const AreaLight& light, std::span<const ShadingPoint> points,
                                               const RuntimeOptions& options) {
    const uint32_t flags = areaLightFlags(options);
    std::vector<AreaLightResult> out(points.size());
    DispatchGrid::list(points.size()).forEachRange([&](std::size_t first, std::size_t end) {
        for (std::size_t i = first; i < end; ++i)
            out[i] =
                areaLightShade(light, areaSurfaceFromPoint(points[i], options.dielectricF0, flags), flags);
    });
    return out;
}

} // namespace ibl
