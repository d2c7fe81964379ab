// Reference renderer for the runtime module (Frostbite 2014, Appendix A, Listings A.1 and A.2): the same
// shading points, the same material model, integrated by brute force against the original lighting, with
// none of the runtime's approximations (split sum, pre-filtered LD, SH, dominant directions, parallax
// correction, distance-based roughness, representative-point sun). Slow; for tests and accuracy reports.
#pragma once

#include "iblbake/runtime/runtime.h"

#include <memory>
#include <optional>
#include <span>
#include <vector>

#include <glm/vec3.hpp>

namespace ibl {

// The radiance a point receives. Environment radiance is the bilinear reconstruction of the cube's texels
// (cubeSampleLevel on its bordered level 0), the same continuous function the runtime's mirror level
// samples, so a mirror's reference is exactly the environment in the reflected direction.
class ReferenceLighting {
  public:
    // A distant environment, plus an optional sun: a disk of uniform radiance E_perp color / (pi sin^2
    // angularRadius) (its illuminance on a surface facing it is exactly E_perp color).
    static ReferenceLighting distant(const CubeMap& environment, std::optional<SunDisk> sun = {});
    // The environment captured at a local probe's capture point (proxy centre + offset along the proxy's
    // axes), projected onto the proxy: a point P receives, from direction l, the capture's radiance in the
    // direction from the capture point to the far intersection of the ray (P, l) with the proxy. A ray that
    // misses the proxy (P outside it) sees the capture in direction l.
    static ReferenceLighting projected(const CubeMap& capture, const ProbeVolume& proxy,
                                       const glm::vec3& captureOffset);

    ReferenceLighting(const ReferenceLighting&);
    ReferenceLighting& operator=(const ReferenceLighting&);
    ~ReferenceLighting();

    // Radiance arriving at `position` from unit direction l (environment and sun).
    glm::dvec3 radiance(const glm::vec3& position, const glm::dvec3& l) const;

    struct Data;
    const Data& data() const { return *data_; }

  private:
    ReferenceLighting();
    std::shared_ptr<const Data> data_;
};

struct ReferenceSettings {
    // Samples of each strategy per point: GGX visible normals, cosine, environment luminance (distant
    // lighting only), sun cone (with a sun only); combined by the balance heuristic.
    std::uint32_t samplesPerStrategy = 2048;
    // Directional albedo E(NoV, alpha) of the energy compensation, by visible-normal sampling.
    std::uint32_t albedoSamples = 4096;
    // GGX alpha is at least this (a lobe 1e-4 rad wide reflects the bilinear environment exactly).
    double minAlpha = 1e-4;
};

struct ReferenceResult {
    glm::dvec3 diffuse{0.0};
    glm::dvec3 specular{0.0};
    glm::dvec3 total() const { return diffuse + specular; }
};

// Outgoing radiance toward view of each point: integral of L(l) f(v, l) <n.l> dl with f the material of
// RuntimeOptions (Lambert or renormalized Disney diffuse; GGX, height-correlated Smith, Schlick with f0 and
// f90; multiple-scattering compensation 1 + f0 (1 / E - 1) with E the exact directional albedo when
// options.energyCompensation). Occlusion terms are not part of it (ao is ignored). fp64 accumulation,
// deterministic (Hammersley points), TBB over points.
std::vector<ReferenceResult> renderReference(const ReferenceLighting& lighting,
                                             std::span<const ShadingPoint> points,
                                             const RuntimeOptions& options,
                                             const ReferenceSettings& settings = {});

// E(NoV, alpha) = integral D V <n.l> dl for f0 = f90 = 1 (single scattering), by visible-normal sampling.
double directionalAlbedo(double NoV, double alpha, std::uint32_t samples);

} // namespace ibl
