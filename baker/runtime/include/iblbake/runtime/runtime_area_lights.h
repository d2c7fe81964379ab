// Area lights for the runtime module (kernels/area_lights.h): sphere, disk and rectangle emitters of
// uniform luminance on the standard material, evaluated on the CPU, and their fp64 brute-force reference.
#pragma once

#include "iblbake/runtime/runtime.h"
#include "iblbake/runtime/runtime_reference.h"

#include <span>
#include <vector>

#include <glm/vec3.hpp>

namespace ibl {

// A light of luminous power `lumens` (Frostbite Table 12 converts it to the luminance it is evaluated in).
// `normal` (disk, rectangle: the emitting side) and `tangent` (rectangle: the width's axis) are normalized
// here; the tangent is made perpendicular to the normal.
AreaLight sphereAreaLight(const glm::vec3& center, float radius, const glm::vec3& color, float lumens);
AreaLight diskAreaLight(const glm::vec3& center, const glm::vec3& normal, float radius,
                        const glm::vec3& color, float lumens);
AreaLight rectangleAreaLight(const glm::vec3& center, const glm::vec3& normal, const glm::vec3& tangent,
                             float width, float height, const glm::vec3& color, float lumens);

// The runtime's diffuse and specular of one light per point (kernels/area_lights.h areaLightShade), for the
// options' specular, diffuse, diffuseModel, f90FromF0 and dielectricF0; energy compensation is not applied
// (it needs the DFG LUT: multiply the specular by shadePoint's 1 + f0 (1 / r - 1) when combining).
std::vector<AreaLightResult> shadeAreaLightCpu(const AreaLight& light, std::span<const ShadingPoint> points,
                                               const RuntimeOptions& options = {});
// The same through OpenCL (kernels/area_lights.cl). Throws ibl::Error on any CL failure.
std::vector<AreaLightResult> shadeAreaLightOpenCL(ocl::Context& context, const AreaLight& light,
                                                  std::span<const ShadingPoint> points,
                                                  const RuntimeOptions& options = {});

struct AreaReferenceSettings {
    // The light's surface is integrated on an n x n midpoint grid of equal-area cells (concentric-mapped for
    // disks; a sphere's visible cap in equal solid angles), n = cellsPerAlpha x (the angle the light spans)
    // / GGX alpha, clamped to [gridSize, maxGridSize]: a lobe of width alpha gets >= cellsPerAlpha cells
    // (gridSize without the specular).
    std::uint32_t gridSize = 512;
    std::uint32_t maxGridSize = 2048;
    double cellsPerAlpha = 16.0;
    double minAlpha = 1e-4; // as ReferenceSettings
};

struct AreaReference {
    ReferenceResult value;
    // |result - result at n / 2| / 3 per channel: Richardson's estimate of the midpoint rule's error, which
    // falls 4x per halved step for the integrand, continuous on the grid's domain (the horizon only bends
    // it: <n.l> is clamped to 0, not cut).
    glm::dvec3 diffuseError{0.0}, specularError{0.0};
};

// Integral over the light's surface of L f(v, l) <n.l> dl, in fp64, with renderReference's material (the
// options' energy compensation ignored, as in shadeAreaLightCpu) and the horizon: only directions with
// <n.l> > 0 and, for disks and rectangles, points in front of the emitting face receive light. A point
// inside a sphere light gets zero. TBB over points.
std::vector<AreaReference> renderAreaLightReference(const AreaLight& light,
                                                    std::span<const ShadingPoint> points,
                                                    const RuntimeOptions& options = {},
                                                    const AreaReferenceSettings& settings = {});

} // namespace ibl
