// The fp64 brute force's shared part (reference_area_lights.cpp, reference_textured_light.cpp): a light's
// surface as a midpoint grid of equal-area cells, the integral of the material over it, the grid's size
// and the error estimate from the grid of half the resolution. Independent of the runtime's light code
// (kernels/area_lights.h): only the AreaLight description is shared.
#pragma once

#include "iblbake/runtime/runtime_area_lights.h"
#include "reference_math.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <span>
#include <vector>

namespace ibl::reference {

// Shirley and Chiu's concentric map of [0, 1]^2 onto the unit disk: area-preserving, so a grid of equal
// squares becomes cells of equal area that stay compact at the centre (a polar grid's would be slivers
// there, too coarse for a mirror's lobe).
inline glm::dvec2 concentricDisk(double s, double t) {
    const double a = 2.0 * s - 1.0, b = 2.0 * t - 1.0;
    if (a == 0.0 && b == 0.0) return {0.0, 0.0};
    if (std::abs(a) > std::abs(b)) {
        const double phi = 0.25 * kPi * (b / a);
        return {a * std::cos(phi), a * std::sin(phi)};
    }
    const double phi = 0.5 * kPi - 0.25 * kPi * (a / b);
    return {b * std::cos(phi), b * std::sin(phi)};
}

// The light's surface as nx x ny cells of equal measure: the direction from the point toward cell (i, j)'s
// centre and the solid angle the cell subtends there (0 for a cell the point sees from behind). Cell
// (i, j) of a rectangle spans s = (i + 0.5) / nx along the tangent and t = (j + 0.5) / ny along the
// bitangent.
struct LightSurface {
    uint32_t shape;
    glm::dvec3 center, normal, tangent, bitangent;
    double halfWidth, halfHeight;

    // Cell (i, j) of nx x ny seen from p: returns the solid angle, writes the direction.
    double cell(const glm::dvec3& p, uint32_t i, uint32_t j, uint32_t nx, uint32_t ny, glm::dvec3& l) const {
        const double s = (double(i) + 0.5) / double(nx), t = (double(j) + 0.5) / double(ny);
        const double cells = double(nx) * double(ny);
        if (shape == IBL_AREA_SPHERE) {
            // The cap visible from p, uniform in solid angle: the disk point's squared radius maps linearly
            // to cos(theta) in [cos(sigma), 1] (area-preserving, as the concentric map).
            const glm::dvec3 toCenter = center - p;
            const double d = glm::length(toCenter);
            const double cosSigma = std::sqrt(1.0 - halfWidth * halfWidth / (d * d));
            const glm::dvec2 q = concentricDisk(s, t);
            const double r2 = glm::dot(q, q);
            const double cosTheta = 1.0 - r2 * (1.0 - cosSigma);
            const double k = r2 > 0.0 ? std::sqrt((1.0 - cosTheta * cosTheta) / r2) : 0.0;
            l = basisAround(toCenter / d).toWorld({q.x * k, q.y * k, cosTheta});
            return 2.0 * kPi * (1.0 - cosSigma) / cells;
        }
        double u, v, area;
        if (shape == IBL_AREA_DISK) {
            const glm::dvec2 q = concentricDisk(s, t) * halfWidth;
            u = q.x, v = q.y;
            area = kPi * halfWidth * halfWidth;
        } else {
            u = (2.0 * s - 1.0) * halfWidth, v = (2.0 * t - 1.0) * halfHeight;
            area = 4.0 * halfWidth * halfHeight;
        }
        glm::dvec3 toPoint = center + u * tangent + v * bitangent - p;
        double d2 = glm::dot(toPoint, toPoint);
        l = toPoint / std::sqrt(d2);
        double cosLight = -glm::dot(l, normal);
        return cosLight > 0.0 ? area / cells * cosLight / d2 : 0.0;
    }

    // The angle the light spans seen from p (at most pi), from its largest half-extent.
    double angularSize(const glm::dvec3& p) const {
        const double d = glm::length(center - p);
        if (shape == IBL_AREA_SPHERE) return 2.0 * std::asin(std::min(halfWidth / d, 1.0));
        return 2.0 * std::atan(std::hypot(halfWidth, shape == IBL_AREA_DISK ? 0.0 : halfHeight) / d);
    }

    // The point receives nothing: behind a disk or rectangle (or on its plane), inside a sphere.
    bool hidden(const glm::dvec3& p) const {
        if (shape == IBL_AREA_SPHERE) return glm::length(p - center) <= halfWidth;
        return glm::dot(p - center, normal) <= 0.0;
    }
};

inline LightSurface lightSurface(const AreaLight& light) {
    LightSurface s;
    s.shape = light.shape;
    s.center = glm::dvec3(light.position);
    s.normal = glm::normalize(glm::dvec3(light.normal));
    s.tangent = glm::normalize(glm::dvec3(light.tangent));
    s.bitangent = glm::cross(s.normal, s.tangent);
    s.halfWidth = light.halfWidth;
    s.halfHeight = light.halfHeight;
    return s;
}

// Sum over the nx x ny grid of emission(i, j) f(v, l) <n.l> dOmega, times the light's radiance.
// `emission(i, j)`: the relative radiance of cell (i, j) (the texel under it; 1 for a uniform light).
template <class Emission>
ReferenceResult integrateLight(const LightSurface& surface, const PointMaterial& m, const glm::dvec3& p,
                               const glm::dvec3& radiance, uint32_t nx, uint32_t ny,
                               const Emission& emission) {
    ReferenceResult r;
    for (uint32_t j = 0; j < ny; ++j)
        for (uint32_t i = 0; i < nx; ++i) {
            glm::dvec3 l;
            const double solidAngle = surface.cell(p, i, j, nx, ny, l);
            const double NoL = glm::dot(m.N, l);
            if (solidAngle <= 0.0 || NoL <= 0.0) continue;
            glm::dvec3 specular, diffuse;
            m.evaluate(l, NoL, specular, diffuse);
            const glm::dvec3 weight = emission(i, j) * solidAngle;
            r.specular += specular * weight;
            r.diffuse += diffuse * weight;
        }
    r.specular *= radiance;
    r.diffuse *= radiance;
    return r;
}

// The grid's size for a point: cellsPerAlpha cells per GGX alpha across the light's angular size, clamped to
// [gridSize, maxGridSize] (gridSize without the specular).
inline uint32_t referenceGridSize(const AreaReferenceSettings& settings, const PointMaterial& m,
                                  double angularSize) {
    const double cells = m.specular ? std::ceil(settings.cellsPerAlpha * angularSize / m.alpha) : 0.0;
    return uint32_t(std::clamp(cells, double(std::max<uint32_t>(settings.gridSize, 2)),
                               double(std::max(settings.maxGridSize, settings.gridSize))));
}

// The fine grid's result with Richardson's error estimate from the grid of half its resolution.
inline AreaReference richardson(const ReferenceResult& fine, const ReferenceResult& coarse) {
    AreaReference out;
    out.value = fine;
    out.diffuseError = glm::abs(fine.diffuse - coarse.diffuse) / 3.0;
    out.specularError = glm::abs(fine.specular - coarse.specular) / 3.0;
    return out;
}

// Each point's reference, zero where the point is behind the light: integrate(m, p, n) with the point's
// material (without energy compensation: the reference is the material's own integral), its position and
// its grid size (referenceGridSize).
template <class IntegratePoint>
std::vector<AreaReference>
referenceAtPoints(const LightSurface& surface, std::span<const ShadingPoint> points,
                  const RuntimeOptions& options, const AreaReferenceSettings& settings,
                  IntegratePoint&& integrate) {
    RuntimeOptions material = options;
    material.energyCompensation = false;
    std::vector<AreaReference> out(points.size());
    tbb::parallel_for(std::size_t(0), points.size(), [&](std::size_t k) {
        const glm::dvec3 p(points[k].position);
        if (surface.hidden(p)) return;
        const PointMaterial m(points[k], material, settings.minAlpha, [](double, double) { return 1.0; });
        out[k] = integrate(m, p, referenceGridSize(settings, m, surface.angularSize(p)));
    });
    return out;
}

} // namespace ibl::reference
