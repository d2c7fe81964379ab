// Area lights on either backend: kernels/area_lights.cl (its work-item kernels/area_light_points.h) over the
// points, and the lights' construction.
#include "area_light_dispatch.h"
#include "iblbake/opencl/dispatch.h"
#include "iblbake/runtime/runtime_area_lights.h"

#include <area_light_points.h>

#include <cstddef>

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

static_assert(sizeof(AreaLightParams) == 76 && offsetof(AreaLightParams, flags) == 64,
              "AreaLightParams must match kernels/area_light_points.h");

namespace {

std::vector<AreaLightResult> shadeAreaLight(const Dispatcher& dispatcher, const AreaLight& light,
                                            std::span<const ShadingPoint> points,
                                            const RuntimeOptions& options) {
    const DeviceArray<ShadingPoint> input = dispatcher.upload("shading points", points);
    return shadeEachTerm(points.size(), options, [&](uint32_t flags) {
        AreaLightParams params{};
        params.light = light;
        params.flags = flags;
        params.dielectricF0 = options.dielectricF0;
        params.pointCount = uint32_t(points.size());
        DispatchOutput result = dispatcher.output(DispatchGrid::list(points.size()));
        dispatcher.run(kernel("area_lights.cl", "shadeAreaLights", shadeAreaLightItem), result, params,
                       input);
        return dispatcher.download(result);
    });
}

} // namespace

std::vector<AreaLightResult> shadeAreaLightCpu(const AreaLight& light, std::span<const ShadingPoint> points,
                                               const RuntimeOptions& options) {
    return shadeAreaLight(Dispatcher(nullptr), light, points, options);
}

std::vector<AreaLightResult> shadeAreaLightOpenCL(ocl::Context& context, const AreaLight& light,
                                                  std::span<const ShadingPoint> points,
                                                  const RuntimeOptions& options) {
    return shadeAreaLight(Dispatcher(&context), light, points, options);
}

} // namespace ibl
