// Brute-force reference of the area lights (runtime_area_lights.h): the integral of L f(v, l) <n.l> over
// the light's surface, in fp64 with reference_math.h's material, on a midpoint grid of equal-area cells,
// and again on the grid of half the resolution for the error estimate (reference_light_surface.h).
#include "iblbake/runtime/runtime_area_lights.h"
#include "reference_light_surface.h"

namespace ibl {

std::vector<AreaReference> renderAreaLightReference(const AreaLight& light,
                                                    std::span<const ShadingPoint> points,
                                                    const RuntimeOptions& options,
                                                    const AreaReferenceSettings& settings) {
    using namespace reference;
    const LightSurface surface = lightSurface(light);
    const glm::dvec3 radiance = glm::dvec3(light.color) * double(light.luminance);
    const auto uniform = [](uint32_t, uint32_t) { return glm::dvec3(1.0); };
    return referenceAtPoints(
        surface, points, options, settings, [&](const PointMaterial& m, const glm::dvec3& p, uint32_t n) {
            return richardson(integrateLight(surface, m, p, radiance, n, n, uniform),
                              integrateLight(surface, m, p, radiance, n / 2, n / 2, uniform));
        });
}

} // namespace ibl
