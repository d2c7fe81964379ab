// Brute-force reference for the runtime (Frostbite Appendix A). Listing A.1 importance samples the GGX NDF
// and Listing A.2 the cosine lobe; here GGX visible normals (Heitz 2018, lower variance), the cosine lobe,
// the environment's luminance and the sun's cone are all sampled and combined with the balance heuristic
// (Veach 1997), so that neither a narrow lobe nor a small bright source is left to chance. Everything is
// in fp64 and independent of the runtime's code except the cube addressing and the bilinear lookup that
// define the environment as a continuous function.
#include "iblbake/core/error.h"
#include "iblbake/runtime/runtime_reference.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

namespace ibl {

namespace {

constexpr double kPi = 3.14159265358979323846;

double radicalInverse(uint32_t bits) {
    bits = (bits << 16u) | (bits >> 16u);
    bits = ((bits & 0x55555555u) << 1u) | ((bits & 0xAAAAAAAAu) >> 1u);
    bits = ((bits & 0x33333333u) << 2u) | ((bits & 0xCCCCCCCCu) >> 2u);
    bits = ((bits & 0x0F0F0F0Fu) << 4u) | ((bits & 0xF0F0F0F0u) >> 4u);
    bits = ((bits & 0x00FF00FFu) << 8u) | ((bits & 0xFF00FF00u) >> 8u);
    return double(bits) * 2.3283064365386963e-10;
}

// Hammersley point i of n, Cranley-Patterson rotated by `shift` (one shift per strategy decorrelates them).
glm::dvec2 samplePoint(uint32_t i, uint32_t n, glm::dvec2 shift) {
    glm::dvec2 u((double(i) + 0.5) / double(n) + shift.x, radicalInverse(i) + shift.y);
    return u - glm::floor(u);
}

struct Basis {
    glm::dvec3 t, b, n;
    glm::dvec3 toWorld(const glm::dvec3& v) const { return v.x * t + v.y * b + v.z * n; }
    glm::dvec3 toLocal(const glm::dvec3& v) const { return {glm::dot(v, t), glm::dot(v, b), glm::dot(v, n)}; }
};

Basis basisAround(const glm::dvec3& n) { // Duff et al. 2017
    double s = std::copysign(1.0, n.z);
    double a = -1.0 / (s + n.z);
    double b = n.x * n.y * a;
    return {{1.0 + s * n.x * n.x * a, s * b, -s * n.x}, {b, s + n.y * n.y * a, -n.y}, n};
}

double ggxD(double NoH, double a2) {
    double f = NoH * NoH * (a2 - 1.0) + 1.0;
    return a2 / (kPi * f * f);
}
double lambdaFactor(double c, double a2) {
    return std::sqrt(a2 + (1.0 - a2) * c * c);
}
// Height-correlated Smith visibility G2 / (4 NoL NoV) and masking G1.
double smithVisibility(double NoV, double NoL, double a2) {
    return 0.5 / (NoL * lambdaFactor(NoV, a2) + NoV * lambdaFactor(NoL, a2));
}
double smithG1(double NoV, double a2) {
    return 2.0 * NoV / (NoV + lambdaFactor(NoV, a2));
}

// Visible normal for a view in the local frame (Heitz 2018, listing 1).
glm::dvec3 sampleVisibleNormal(const glm::dvec3& v, double alpha, glm::dvec2 u) {
    glm::dvec3 vh = glm::normalize(glm::dvec3(alpha * v.x, alpha * v.y, v.z));
    double lensq = vh.x * vh.x + vh.y * vh.y;
    glm::dvec3 t1 = lensq > 0.0 ? glm::dvec3(-vh.y, vh.x, 0.0) / std::sqrt(lensq) : glm::dvec3(1.0, 0.0, 0.0);
    glm::dvec3 t2 = glm::cross(vh, t1);
    double r = std::sqrt(u.x), phi = 2.0 * kPi * u.y;
    double p1 = r * std::cos(phi), p2 = r * std::sin(phi);
    double s = 0.5 * (1.0 + vh.z);
    p2 = (1.0 - s) * std::sqrt(std::max(0.0, 1.0 - p1 * p1)) + s * p2;
    glm::dvec3 nh = p1 * t1 + p2 * t2 + std::sqrt(std::max(0.0, 1.0 - p1 * p1 - p2 * p2)) * vh;
    return glm::normalize(glm::dvec3(alpha * nh.x, alpha * nh.y, std::max(1e-12, nh.z)));
}

double luminance(const glm::vec4& c) {
    return 0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z;
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

    glm::dvec3 environment(const glm::dvec3& l) const {
        vec3 c = cubeSampleLevel(env.data.data(), env.layout, 0, cubeCoordFromDirection(vec3(l)));
        return glm::dvec3(c);
    }
    bool inSun(const glm::dvec3& l) const { return sun && glm::dot(l, sunDirection) >= sunCos; }

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

LdPyramid baseLevelPyramid(const CubeMap& cube) {
    CubeMapChain chain;
    chain.levels.push_back(cube);
    return ldPyramidFromChain(chain);
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
    if (sun && sun->illuminance > 0.0f) {
        d->sun = sun;
        d->sunDirection = glm::normalize(glm::dvec3(sun->direction));
        double radius = std::max(double(sun->angularRadius), 1e-5);
        d->sunCos = std::cos(radius);
        d->sunSolidAngle = 2.0 * kPi * (1.0 - d->sunCos);
        double projected = kPi * std::sin(radius) * std::sin(radius);
        d->sunRadiance = glm::dvec3(sun->color) * double(sun->illuminance) / projected;
    }
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

glm::dvec3 ReferenceLighting::radiance(const glm::vec3& position, const glm::dvec3& l) const {
    const Data& d = *data_;
    if (d.projected) {
        ParallaxHit h = parallaxCorrect(d.proxy, d.captureOffset, position, vec3(l));
        return d.environment(h.hit ? glm::dvec3(h.direction) : l);
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
    const bool sunSampling = !d.projected && d.sun.has_value();
    const uint32_t n = settings.samplesPerStrategy;
    std::vector<ReferenceResult> out(points.size());

    tbb::parallel_for(std::size_t(0), points.size(), [&](std::size_t index) {
        const ShadingPoint& sp = points[index];
        auto safeUnit = [](glm::dvec3 v, glm::dvec3 fallback) {
            double l = glm::length(v);
            return l > 1e-30 ? v / l : fallback;
        };
        const glm::dvec3 N = safeUnit(glm::dvec3(sp.normal), {0.0, 1.0, 0.0});
        const Basis frame = basisAround(N);
        glm::dvec3 vLocal = frame.toLocal(safeUnit(glm::dvec3(sp.view), N));
        // A view at or below the horizon is bent up to grazing (NoV = 1e-4), keeping its azimuth.
        if (vLocal.z < 1e-4) {
            double h = std::hypot(vLocal.x, vLocal.y);
            vLocal = h > 0.0 ? glm::dvec3(vLocal.x / h * std::sqrt(1.0 - 1e-8),
                                          vLocal.y / h * std::sqrt(1.0 - 1e-8), 1e-4)
                             : glm::dvec3(0.0, 0.0, 1.0);
        }
        const glm::dvec3 V = frame.toWorld(vLocal);
        const double NoV = vLocal.z;
        const double r = std::clamp(double(sp.perceptualRoughness), 0.0, 1.0);
        const double alpha = std::max(r * r, settings.minAlpha), a2 = alpha * alpha;
        const double metallic = std::clamp(double(sp.metallic), 0.0, 1.0);
        const glm::dvec3 base(sp.baseColor);
        const glm::dvec3 diffuseColor = base * (1.0 - metallic);
        const glm::dvec3 f0 = glm::dvec3(double(options.dielectricF0) * (1.0 - metallic)) + base * metallic;
        const double f90 =
            options.f90FromF0 ? std::clamp(50.0 * 0.33f * (f0.x + f0.y + f0.z), 0.0, 1.0) : 1.0;
        glm::dvec3 compensation(1.0);
        if (options.energyCompensation && options.specular)
            compensation = 1.0 + f0 * (1.0 / directionalAlbedo(NoV, alpha, settings.albedoSamples) - 1.0);
        const double g1 = smithG1(NoV, a2);
        const bool disney = options.diffuseModel == DiffuseModel::Disney;
        const double energyBias = 0.5 * r, energyFactor = 1.0 + (1.0 / 1.51 - 1.0) * r;

        auto pdfSum = [&](const glm::dvec3& l, double NoL) {
            glm::dvec3 h = glm::normalize(V + l);
            double NoH = glm::dot(N, h), VoH = glm::dot(V, h);
            double p = NoL / kPi; // cosine
            if (NoH > 0.0 && VoH > 0.0) p += g1 * ggxD(NoH, a2) / (4.0 * NoV);
            if (envSampling) p += d.environmentPdf(l);
            if (sunSampling && d.inSun(l)) p += 1.0 / d.sunSolidAngle;
            return p * double(n);
        };

        glm::dvec3 specular(0.0), diffuse(0.0);
        auto accumulate = [&](const glm::dvec3& l) {
            double NoL = glm::dot(N, l);
            if (!(NoL > 0.0)) return;
            glm::dvec3 Li = lighting.radiance(sp.position, l);
            double p = pdfSum(l, NoL);
            if (!(p > 0.0)) return;
            glm::dvec3 h = glm::normalize(V + l);
            double NoH = std::max(glm::dot(N, h), 0.0), LoH = std::clamp(glm::dot(l, h), 0.0, 1.0);
            if (options.specular) {
                double fc = std::pow(1.0 - LoH, 5.0);
                glm::dvec3 F = f0 + (f90 - f0) * fc;
                double dv = ggxD(NoH, a2) * smithVisibility(NoV, NoL, a2);
                specular += Li * F * compensation * (dv * NoL / p);
            }
            if (options.diffuse) {
                double fd = 1.0;
                if (disney) {
                    double fd90 = energyBias + 2.0 * LoH * LoH * r;
                    double lightScatter = 1.0 + (fd90 - 1.0) * std::pow(1.0 - NoL, 5.0);
                    double viewScatter = 1.0 + (fd90 - 1.0) * std::pow(1.0 - NoV, 5.0);
                    fd = lightScatter * viewScatter * energyFactor;
                }
                diffuse += Li * diffuseColor * (fd / kPi * NoL / p);
            }
        };

        for (uint32_t i = 0; i < n; ++i) {
            // GGX visible normals.
            glm::dvec3 hl = sampleVisibleNormal(vLocal, alpha, samplePoint(i, n, {0.0, 0.0}));
            accumulate(frame.toWorld(2.0 * glm::dot(vLocal, hl) * hl - vLocal));
            // Cosine lobe (Malley).
            glm::dvec2 u = samplePoint(i, n, {0.5, 0.25});
            double rr = std::sqrt(u.x), phi = 2.0 * kPi * u.y;
            accumulate(
                frame.toWorld({rr * std::cos(phi), rr * std::sin(phi), std::sqrt(std::max(0.0, 1.0 - u.x))}));
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
