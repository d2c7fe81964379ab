// Brute-force reference for the runtime (Frostbite Appendix A). Listing A.1 importance samples the GGX NDF
// and Listing A.2 the cosine lobe; here GGX visible normals (Heitz 2018, lower variance), the cosine lobe,
// the environment's luminance and the sun's cone are all sampled and combined with the balance heuristic
// (Veach 1997), so that neither a narrow lobe nor a small bright source is left to chance. Everything is
// in fp64 and independent of the runtime's code except the cube addressing and the bilinear lookup that
// define the environment as a continuous function.
#include "iblbake/core/error.h"
#include "iblbake/runtime/runtime_reference.h"
#include "reference_math.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

namespace ibl {

namespace {

using namespace reference;

double luminance(const glm::vec4& c) {
    return reference::luminance(glm::dvec3(c));
}

} // namespace

double directionalAlbedo(double NoV, double alpha, std::uint32_t samples) {
    NoV = std::clamp(NoV, 1e-6, 1.0);
    const double a2 = alpha * alpha;
    const glm::dvec3 v(std::sqrt(1.0 - NoV * NoV), 0.0, NoV);
    const double g1 = smithG1(NoV, a2);
    double sum = 0.0;
    for (uint32_t i = 0; i < samples; ++i) {
        glm::dvec3 h = sampleVisibleNormal(v, alpha, samplePoint(i, samples, {0.0, 0.0}));
        double NoL = 2.0 * glm::dot(v, h) * h.z - NoV;
        if (NoL <= 0.0) continue;
        double g2 = 4.0 * NoV * NoL * smithVisibility(NoV, NoL, a2);
        sum += g2 / g1;
    }
    return sum / double(samples);
}

struct ReferenceLighting::Data {
    bool projected = false;
    LdPyramid env; // level 0 only: the bilinear reconstruction
    int faceSize = 0;
    // Environment sampling (distant only): texel probabilities and their CDF over 6 n^2 texels.
    std::vector<double> probability, cdf;
    std::optional<SunDisk> sun;
    glm::dvec3 sunDirection{0.0}, sunRadiance{0.0};
    double sunCos = 1.0, sunSolidAngle = 0.0;
    ProbeVolume proxy{};
    glm::vec3 captureOffset{0.0f};
    // projectedWithVisibility: the capture's visibility (a scalar pyramid beside env) and the distant map
    // seen where it is below 1.
    bool background = false;
    LdPyramid distant;

    // 1 - the bilinear visibility of the capture in direction l (0 without visibility).
    double transparency(const glm::dvec3& l) const {
        if (env.visibility.empty()) return 0.0;
        return 1.0 - double(cubeSampleLevelScalar(env.visibility.data(), env.layout, 0,
                                                  cubeCoordFromDirection(vec3(l))));
    }

    glm::dvec3 environment(const glm::dvec3& l) const {
        vec3 c = cubeSampleLevel(env.data.data(), env.layout, 0, cubeCoordFromDirection(vec3(l)));
        return glm::dvec3(c);
    }
    bool inSun(const glm::dvec3& l) const { return sun && glm::dot(l, sunDirection) >= sunCos; }

    // A uniform disk whose illuminance on a surface facing it is E_perp color.
    void setSun(const std::optional<SunDisk>& disk) {
        if (!disk || !(disk->illuminance > 0.0f)) return;
        sun = disk;
        sunDirection = glm::normalize(glm::dvec3(disk->direction));
        double radius = std::max(double(disk->angularRadius), 1e-5);
        sunCos = std::cos(radius);
        sunSolidAngle = 2.0 * kPi * (1.0 - sunCos);
        const double projectedSolidAngle = kPi * std::sin(radius) * std::sin(radius);
        sunRadiance = glm::dvec3(disk->color) * double(disk->illuminance) / projectedSolidAngle;
    }

    double environmentPdf(const glm::dvec3& l) const {
        CubeCoord c = cubeCoordFromDirection(vec3(l));
        const int n = faceSize;
        int x = std::clamp(int(c.s * float(n)), 0, n - 1), y = std::clamp(int(c.t * float(n)), 0, n - 1);
        double a = 2.0 * c.s - 1.0, b = 2.0 * c.t - 1.0;
        double texelArea = (2.0 / n) * (2.0 / n);
        return probability[std::size_t(c.face) * n * n + std::size_t(y) * n + std::size_t(x)] *
               std::pow(1.0 + a * a + b * b, 1.5) / texelArea;
    }

    glm::dvec3 sampleEnvironment(glm::dvec2 u) const {
        auto it = std::upper_bound(cdf.begin(), cdf.end(), u.x);
        std::size_t t = std::size_t(
            std::clamp<std::ptrdiff_t>(it - cdf.begin() - 1, 0, std::ptrdiff_t(probability.size()) - 1));
        double width = cdf[t + 1] - cdf[t];
        double fx = width > 0.0 ? std::clamp((u.x - cdf[t]) / width, 0.0, 1.0) : 0.5;
        const std::size_t n = std::size_t(faceSize);
        int face = int(t / (n * n));
        std::size_t texel = t % (n * n);
        double s = (double(texel % n) + fx) / double(n), tt = (double(texel / n) + u.y) / double(n);
        return glm::normalize(glm::dvec3(cubeFaceDirection(face, float(s), float(tt))));
    }
};

ReferenceLighting::ReferenceLighting() = default;
ReferenceLighting::ReferenceLighting(const ReferenceLighting&) = default;
ReferenceLighting& ReferenceLighting::operator=(const ReferenceLighting&) = default;
ReferenceLighting::~ReferenceLighting() = default;

namespace {

LdPyramid baseLevelPyramid(const CubeMap& cube, ChainAlpha alpha = ChainAlpha::Ignore) {
    CubeMapChain chain;
    chain.levels.push_back(cube);
    return ldPyramidFromChain(chain, MipMapping::Frostbite, alpha);
}

} // namespace

ReferenceLighting ReferenceLighting::distant(const CubeMap& environment, std::optional<SunDisk> sun) {
    auto d = std::make_shared<Data>();
    d->env = baseLevelPyramid(environment);
    d->faceSize = environment.faceSize;
    const int n = environment.faceSize;
    const std::size_t count = 6 * std::size_t(n) * n;
    // 90% by luminance x solid angle, 10% by solid angle: every direction keeps a density, also where the
    // bilinear reconstruction spreads a texel into a dark neighbour.
    std::vector<double> byLuminance(count), bySolidAngle(count);
    double sumL = 0.0, sumO = 0.0;
    for (int f = 0; f < 6; ++f)
        for (int y = 0; y < n; ++y)
            for (int x = 0; x < n; ++x) {
                std::size_t t = std::size_t(f) * n * n + std::size_t(y) * n + std::size_t(x);
                double omega = std::abs(double(cubeTexelSolidAngle(x, y, n)));
                double lum = std::max(0.0, luminance(environment.faces[f].at(x, y)));
                byLuminance[t] = std::isfinite(lum) ? lum * omega : 0.0;
                bySolidAngle[t] = omega;
                sumL += byLuminance[t];
                sumO += omega;
            }
    d->probability.resize(count);
    d->cdf.assign(count + 1, 0.0);
    const double mixL = sumL > 0.0 ? 0.9 : 0.0;
    for (std::size_t t = 0; t < count; ++t) {
        d->probability[t] =
            (mixL > 0.0 ? mixL * byLuminance[t] / sumL : 0.0) + (1.0 - mixL) * bySolidAngle[t] / sumO;
        d->cdf[t + 1] = d->cdf[t] + d->probability[t];
    }
    for (double& c : d->cdf)
        c /= d->cdf.back();
    d->setSun(sun);
    ReferenceLighting r;
    r.data_ = d;
    return r;
}

ReferenceLighting ReferenceLighting::projected(const CubeMap& capture, const ProbeVolume& proxy,
                                               const glm::vec3& captureOffset) {
    auto d = std::make_shared<Data>();
    d->projected = true;
    d->env = baseLevelPyramid(capture);
    d->faceSize = capture.faceSize;
    d->proxy = proxy;
    d->captureOffset = captureOffset;
    ReferenceLighting r;
    r.data_ = d;
    return r;
}

ReferenceLighting ReferenceLighting::projectedWithVisibility(const CubeMap& premultipliedCapture,
                                                             const ProbeVolume& proxy,
                                                             const glm::vec3& captureOffset,
                                                             const CubeMap& distant,
                                                             std::optional<SunDisk> sun) {
    auto d = std::make_shared<Data>();
    d->projected = true;
    d->env = baseLevelPyramid(premultipliedCapture, ChainAlpha::PremultipliedVisibility);
    d->faceSize = premultipliedCapture.faceSize;
    d->proxy = proxy;
    d->captureOffset = captureOffset;
    d->background = true;
    d->distant = baseLevelPyramid(distant);
    d->setSun(sun);
    ReferenceLighting r;
    r.data_ = d;
    return r;
}

glm::dvec3 ReferenceLighting::radiance(const glm::vec3& position, const glm::dvec3& l) const {
    const Data& d = *data_;
    if (d.projected) {
        ParallaxHit h = parallaxCorrect(d.proxy, d.captureOffset, position, vec3(l));
        const glm::dvec3 towardProxy = h.hit ? glm::dvec3(h.direction) : l;
        glm::dvec3 c = d.environment(towardProxy);
        if (d.background) {
            glm::dvec3 far = glm::dvec3(
                cubeSampleLevel(d.distant.data.data(), d.distant.layout, 0, cubeCoordFromDirection(vec3(l))));
            if (d.inSun(l)) far += d.sunRadiance;
            c += d.transparency(towardProxy) * far;
        }
        return c;
    }
    glm::dvec3 c = d.environment(l);
    if (d.inSun(l)) c += d.sunRadiance;
    return c;
}

std::vector<ReferenceResult> renderReference(const ReferenceLighting& lighting,
                                             std::span<const ShadingPoint> points,
                                             const RuntimeOptions& options,
                                             const ReferenceSettings& settings) {
    if (settings.samplesPerStrategy == 0) throw Error("reference: zero samples per strategy");
    const ReferenceLighting::Data& d = lighting.data();
    const bool envSampling = !d.projected;
    const bool sunSampling = d.sun.has_value();
    const uint32_t n = settings.samplesPerStrategy;
    std::vector<ReferenceResult> out(points.size());

    tbb::parallel_for(std::size_t(0), points.size(), [&](std::size_t index) {
        const PointMaterial m(points[index], options, settings.minAlpha, [&](double NoV, double alpha) {
            return directionalAlbedo(NoV, alpha, settings.albedoSamples);
        });
        const glm::vec3 position = points[index].position;

        auto pdfSum = [&](const glm::dvec3& l, double NoL) {
            double p = NoL / kPi + m.visibleNormalPdf(l); // cosine, visible normals
            if (envSampling) p += d.environmentPdf(l);
            if (sunSampling && d.inSun(l)) p += 1.0 / d.sunSolidAngle;
            return p * double(n);
        };

        glm::dvec3 specular(0.0), diffuse(0.0);
        auto accumulate = [&](const glm::dvec3& l) {
            double NoL = glm::dot(m.N, l);
            if (!(NoL > 0.0)) return;
            glm::dvec3 Li = lighting.radiance(position, l);
            double p = pdfSum(l, NoL);
            if (!(p > 0.0)) return;
            glm::dvec3 s, dd;
            m.evaluate(l, NoL, s, dd);
            specular += Li * s / p;
            diffuse += Li * dd / p;
        };

        for (uint32_t i = 0; i < n; ++i) {
            // GGX visible normals.
            accumulate(m.sampleVisibleNormalDirection(samplePoint(i, n, {0.0, 0.0})));
            accumulate(m.sampleCosineDirection(samplePoint(i, n, {0.5, 0.25}))); // cosine lobe
            if (envSampling) accumulate(d.sampleEnvironment(samplePoint(i, n, {0.25, 0.5})));
            if (sunSampling) {
                glm::dvec2 w = samplePoint(i, n, {0.75, 0.75});
                double cosT = 1.0 - w.x * (1.0 - d.sunCos),
                       sinT = std::sqrt(std::max(0.0, 1.0 - cosT * cosT));
                double ph = 2.0 * kPi * w.y;
                accumulate(
                    basisAround(d.sunDirection).toWorld({sinT * std::cos(ph), sinT * std::sin(ph), cosT}));
            }
        }
        out[index].specular = specular;
        out[index].diffuse = diffuse;
    });
    return out;
}

} // namespace ibl
