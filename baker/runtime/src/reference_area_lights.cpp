// Brute-force reference of the area lights (runtime_area_lights.h): the integral of L f(v, l) <n.l> over
// the light's surface, in fp64 with reference_math.h's material, on a midpoint grid of equal-area cells,
// and again on the grid of half the resolution for the error estimate (reference_light_surface.h).
#include "iblbake/runtime/runtime_area_lights.h"
#include "reference_light_surface.h"

#include <tbb/parallel_for.h>

namespace ibl {

std::vector<AreaReference> renderAreaLightReference(const AreaLight& light,
                                                    std::span<const ShadingPoint> points,
                                                    const RuntimeOptions& options,
                                                    const AreaReferenceSettings& settings) {
    using namespace reference;
    RuntimeOptions material = options;
    material.energyCompensation = false;
    const LightSurface surface = lightSurface(light);
    const glm::dvec3 radiance = glm::dvec3(light.color) * double(light.luminance);
    const auto uniform = [](uint32_t, uint32_t) { return glm::dvec3(1.0); };
    std::vector<AreaReference> out(points.size());
    tbb::parallel_for(std::size_t(0), points.size(), [&](std::size_t k) {
        const glm::dvec3 p(points[k].position);
        if (surface.hidden(p)) return;
        const PointMaterial m(points[k], material, settings.minAlpha, [](double, double) { return 1.0; });
        const uint32_t n = referenceGridSize(settings, m, surface.angularSize(p));
        out[k] = richardson(integrateLight(surface, m, p, radiance, n, n, uniform),
                            integrateLight(surface, m, p, radiance, n / 2, n / 2, uniform));
    });
    return out;
}

} // namespace ibl
