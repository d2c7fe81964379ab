// Reference renderer for the runtime module (Frostbite 2014, Appendix A, Listings A.1 and A.2): the same
// shading points, the same material model, integrated by brute force against the original lighting, with
// none of the runtime's approximations (split sum, pre-filtered LD, SH, dominant directions, parallax
// correction, distance-based roughness, representative-point sun). Slow; for tests and accuracy reports.
#pragma once

#include "iblbake/runtime/runtime.h"

#include <functional>
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
    // The same with the capture's visibility (Frostbite 4.9.1.2; RGB colour x visibility, A the visibility,
    // as bakeSpecularWithVisibility takes it) and a distant map behind: from direction l, the capture's
    // bilinear RGB toward the proxy plus (1 - its bilinear visibility there) x the distant map in l. What the
    // 4.9.5 composition of one local probe of influence weight 1 and the distant probe approximates. An
    // optional sun (as in distant()) lies behind the capture like the distant map: seen where the capture
    // is transparent, as a shadow-mapped analytic sun is seen through a window.
    static ReferenceLighting projectedWithVisibility(const CubeMap& premultipliedCapture,
                                                     const ProbeVolume& proxy, const glm::vec3& captureOffset,
                                                     const CubeMap& distant, std::optional<SunDisk> sun = {});

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

// The converged reference of distant lighting (reference_converged.cpp has the method): the same integral
// as renderReference's for ReferenceLighting::distant(environment), with the bright texels integrated
// deterministically and the dim rest by a fixed stratified sample set (visible normals, cosine and, unless
// the dim rest is nearly flat, its luminance), with its own error estimated per
// point (errorEstimate, per channel): the samples come in two independent halves (Hammersley sets under
// different rotations), whose half difference has the size of the results' sampling error, and the bright
// texels' grid is also evaluated at half its resolution, whose difference bounds the results' quadrature
// error (the midpoint rule's falls 4x per halved step; texels taken in one step add the rule's a-priori
// bound). For a sum of points, the sum of their estimates bounds the change of the sum.
// The bright texels of a cube (indices (face n + y) n + x): luminance above `factor` times the solid-angle
// mean, at most `maxCount` (the brightest). What the converged references integrate deterministically.
inline constexpr double kBrightFactor = 16.0;
inline constexpr std::size_t kMaxBrightTexels = 4096;
std::vector<std::size_t> brightTexels(const CubeMap& cube, double factor = kBrightFactor,
                                      std::size_t maxCount = kMaxBrightTexels);

struct ConvergedReferenceSettings {
    std::uint32_t samples = 1024; // per strategy (visible normals, cosine, environment) over the dim rest
    double stepsPerScale = 8.0;   // sub-texel steps per local angular scale of the BRDF (bright texels)
    double brightFactor = 16.0;   // bright: luminance above this times the solid-angle mean
    std::size_t maxBrightTexels = 4096; // the brightest ones when more pass
    std::uint32_t albedoSamples = 4096; // as ReferenceSettings
    double minAlpha = 1e-4;
};

struct ConvergedReference {
    std::vector<ReferenceResult> results;
    std::vector<glm::dvec3> errorEstimate; // per point and channel, >= 0
    std::size_t brightTexels = 0;          // integrated deterministically
};

ConvergedReference renderConvergedReference(const CubeMap& environment, std::span<const ShadingPoint> points,
                                            const RuntimeOptions& options,
                                            const ConvergedReferenceSettings& settings = {});

// The converged reference of points in groups (the preview's roughness columns: `groupOfPoint`, one id in
// [0, groups) per point), each group at the least effort that meets `targetError` (issue 46): a group
// starts at `firstSamples` per strategy and the grid of `settings`, and while kEstimateMargin times the sum
// of its points' errorEstimate luminance exceeds targetError times the sum of their results' luminance (the
// estimate is the error's expected size, no bound: it read up to 1.32x under the actual error against a
// 16,384-sample run on studio_small_03, `tests/bench/reference_check`), the part whose
// estimate is larger is refined: the samples doubled by a batch of as many as all before under fresh
// rotations (up to settings.samples x 16), or the grid's steps (up to 4 x settings.stepsPerScale). The
// estimate is the fixed-effort one's (the half difference of all samples, the grid against its half), of
// the effort each group stopped at (groupSamples, groupStepsPerScale). `progress` (may be empty) is called
// after each round with the groups done and an estimate of the seconds left: the rounds' time per
// point-sample times the samples the groups left need if their estimates fall as one over the square root
// of their samples.
inline constexpr double kEstimateMargin = 1.35;
struct AdaptiveReferenceSettings {
    double targetError = 0.005; // per group, relative (luminance)
    // Per strategy. On the park map at 64 (two halves of 32) the estimate stated up to 1.3x less than the
    // actual error against a 16,384-sample run, and 0.57% for a 0.5% target; at 128 up to 1.2x, all <= 0.47%.
    std::uint32_t firstSamples = 128;
};
struct AdaptiveReference {
    ConvergedReference reference;
    std::vector<std::uint32_t> groupSamples;
    std::vector<double> groupStepsPerScale;
    std::vector<double> groupErrorEstimate; // relative, as compared with targetError
};
using ReferenceProgress = std::function<void(int groupsDone, int groups, double secondsLeft)>;
AdaptiveReference renderAdaptiveReference(const CubeMap& environment, std::span<const ShadingPoint> points,
                                          std::span<const int> groupOfPoint, const RuntimeOptions& options,
                                          const ConvergedReferenceSettings& settings,
                                          const AdaptiveReferenceSettings& adaptive,
                                          const ReferenceProgress& progress = {});

// E(NoV, alpha) = integral D V <n.l> dl for f0 = f90 = 1 (single scattering), by visible-normal sampling.
double directionalAlbedo(double NoV, double alpha, std::uint32_t samples);

} // namespace ibl
