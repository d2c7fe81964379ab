// Brute-force reference of the textured rectangle light (runtime_light_card.h): the integral of
// L(x) f(v, l) <n.l> over the rectangle in fp64 (reference_light_surface.h), L(x) the emission texel under
// x, on a midpoint grid that is a multiple of the texture (every cell inside one texel), and again at half
// the resolution for the error estimate. Independent of the runtime's light code (kernels/textured_light.h,
// kernels/area_lights.h): only the AreaLight description is shared.
#include "iblbake/runtime/runtime_light_card.h"
#include "reference_light_surface.h"

namespace ibl {

std::vector<AreaReference> renderTexturedLightReference(const AreaLight& light, const ImageRGBA& emission,
                                                        std::span<const ShadingPoint> points,
                                                        const RuntimeOptions& options,
                                                        const AreaReferenceSettings& settings) {
    using namespace reference;
    LightSurface surface = lightSurface(light);
    surface.shape = IBL_AREA_RECTANGLE;
    const glm::dvec3 radiance = glm::dvec3(light.color) * double(light.luminance);
    return referenceAtPoints(
        surface, points, options, settings, [&](const PointMaterial& m, const glm::dvec3& p, uint32_t n) {
            // Multiples of twice the texture's size, so that the fine and the coarse grid both align with
            // texels.
            auto aligned = [&](uint32_t size) {
                return std::max<uint32_t>(2 * size, (n + 2 * size - 1) / (2 * size) * (2 * size));
            };
            const uint32_t nx = aligned(uint32_t(emission.width)), ny = aligned(uint32_t(emission.height));
            // Cell (i, j) of nx x ny: u = s along the tangent, v = 1 - t (v = 0 at the +bitangent edge).
            auto texels = [&](uint32_t cellsX, uint32_t cellsY) {
                return [&emission, cellsX, cellsY](uint32_t i, uint32_t j) {
                    const int x = int(uint64_t(i) * uint64_t(emission.width) / cellsX);
                    const int y = int(uint64_t(cellsY - 1 - j) * uint64_t(emission.height) / cellsY);
                    return glm::dvec3(glm::vec3(emission.at(x, y)));
                };
            };
            return richardson(
                integrateLight(surface, m, p, radiance, nx, ny, texels(nx, ny)),
                integrateLight(surface, m, p, radiance, nx / 2, ny / 2, texels(nx / 2, ny / 2)));
        });
}

} // namespace ibl
