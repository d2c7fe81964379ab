// Brute-force reference of the textured rectangle light (runtime_light_card.h): the integral of
// L(x) f(v, l) <n.l> over the rectangle in fp64 with reference_math.h's material, L(x) the emission texel
// under x, on a midpoint grid that is a multiple of the texture (every cell inside one texel), and again at
// half the resolution for the error estimate. Independent of the runtime's light code (kernels/
// textured_light.h, kernels/area_lights.h): only the AreaLight description is shared.
#include "iblbake/runtime/runtime_light_card.h"
#include "reference_math.h"

#include <tbb/parallel_for.h>

#include <cmath>

namespace ibl {

namespace {

using namespace reference;

struct TexturedRectangle {
    glm::dvec3 center, normal, tangent, bitangent;
    double halfWidth, halfHeight;
    const ImageRGBA* emission;

    // Sum over nx x ny cells of L f <n.l> dOmega.
    ReferenceResult integrate(const PointMaterial& m, const glm::dvec3& p, const glm::dvec3& radiance,
                              std::uint32_t nx, std::uint32_t ny) const {
        ReferenceResult r;
        const double cellArea = 4.0 * halfWidth * halfHeight / double(nx) / double(ny);
        for (std::uint32_t j = 0; j < ny; ++j)
            for (std::uint32_t i = 0; i < nx; ++i) {
                const double u = (double(i) + 0.5) / double(nx), v = (double(j) + 0.5) / double(ny);
                const glm::dvec3 toPoint = center + (2.0 * u - 1.0) * halfWidth * tangent +
                                           (1.0 - 2.0 * v) * halfHeight * bitangent - p;
                const double d2 = glm::dot(toPoint, toPoint);
                const glm::dvec3 l = toPoint / std::sqrt(d2);
                const double cosLight = -glm::dot(l, normal), NoL = glm::dot(m.N, l);
                if (cosLight <= 0.0 || NoL <= 0.0) continue;
                const int x = std::min(int(u * emission->width), emission->width - 1);
                const int y = std::min(int(v * emission->height), emission->height - 1);
                const glm::dvec3 texel(glm::vec3(emission->at(x, y)));
                glm::dvec3 specular, diffuse;
                m.evaluate(l, NoL, specular, diffuse);
                const double solidAngle = cellArea * cosLight / d2;
                r.specular += specular * texel * solidAngle;
                r.diffuse += diffuse * texel * solidAngle;
            }
        r.specular *= radiance;
        r.diffuse *= radiance;
        return r;
    }
};

} // namespace

std::vector<AreaReference> renderTexturedLightReference(const AreaLight& light, const ImageRGBA& emission,
                                                        std::span<const ShadingPoint> points,
                                                        const RuntimeOptions& options,
                                                        const AreaReferenceSettings& settings) {
    RuntimeOptions material = options;
    material.energyCompensation = false;
    TexturedRectangle rect;
    rect.center = glm::dvec3(light.position);
    rect.normal = glm::normalize(glm::dvec3(light.normal));
    rect.tangent = glm::normalize(glm::dvec3(light.tangent));
    rect.bitangent = glm::cross(rect.normal, rect.tangent);
    rect.halfWidth = light.halfWidth;
    rect.halfHeight = light.halfHeight;
    rect.emission = &emission;
    const glm::dvec3 radiance = glm::dvec3(light.color) * double(light.luminance);
    std::vector<AreaReference> out(points.size());
    tbb::parallel_for(std::size_t(0), points.size(), [&](std::size_t k) {
        const glm::dvec3 p(points[k].position);
        if (glm::dot(p - rect.center, rect.normal) <= 0.0) return;
        const PointMaterial m(points[k], material, settings.minAlpha, [](double, double) { return 1.0; });
        const double d = glm::length(rect.center - p);
        const double angle = 2.0 * std::atan(std::hypot(rect.halfWidth, rect.halfHeight) / d);
        const double cells = m.specular ? std::ceil(settings.cellsPerAlpha * angle / m.alpha) : 0.0;
        const std::uint32_t n =
            std::uint32_t(std::clamp(cells, double(std::max<std::uint32_t>(settings.gridSize, 2)),
                                     double(std::max(settings.maxGridSize, settings.gridSize))));
        // Multiples of twice the texture's size, so that the fine and the coarse grid both align with texels.
        auto aligned = [&](std::uint32_t size) {
            return std::max<std::uint32_t>(2 * size, (n + 2 * size - 1) / (2 * size) * (2 * size));
        };
        const std::uint32_t nx = aligned(std::uint32_t(emission.width)),
                            ny = aligned(std::uint32_t(emission.height));
        const ReferenceResult fine = rect.integrate(m, p, radiance, nx, ny);
        const ReferenceResult coarse = rect.integrate(m, p, radiance, nx / 2, ny / 2);
        out[k].value = fine;
        out[k].diffuseError = glm::abs(fine.diffuse - coarse.diffuse) / 3.0;
        out[k].specularError = glm::abs(fine.specular - coarse.specular) / 3.0;
    });
    return out;
}

} // namespace ibl
