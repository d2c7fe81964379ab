// What the two brute-force renderers of runtime_reference.h share, all in fp64 and independent of the
// runtime's shading code (only the bit reversal of kernels/sampling.h is shared): Hammersley points, GGX
// with height-correlated Smith visibility, visible-normal sampling, and the material model of a shading
// point (Frostbite 2014, Appendix A; Heitz 2018).
#pragma once

#include "iblbake/core/numeric.h"
#include "iblbake/runtime/runtime_reference.h"

#include <sampling.h>

#include <algorithm>
#include <cmath>
#include <cstdint>

#include <glm/geometric.hpp>

namespace ibl::reference {

// The radical inverse of kernels/sampling.h in fp64.
inline double radicalInverse(std::uint32_t bits) {
    return double(reverseBits32(bits)) * 2.3283064365386963e-10;
}

// Hammersley point i of n, Cranley-Patterson rotated by `shift` (one shift per strategy decorrelates them).
inline glm::dvec2 samplePoint(std::uint32_t i, std::uint32_t n, glm::dvec2 shift) {
    glm::dvec2 u((double(i) + 0.5) / double(n) + shift.x, radicalInverse(i) + shift.y);
    return u - glm::floor(u);
}

struct Basis {
    glm::dvec3 t, b, n;
    glm::dvec3 toWorld(const glm::dvec3& v) const { return v.x * t + v.y * b + v.z * n; }
    glm::dvec3 toLocal(const glm::dvec3& v) const { return {glm::dot(v, t), glm::dot(v, b), glm::dot(v, n)}; }
};

inline Basis basisAround(const glm::dvec3& n) { // Duff et al. 2017
    double s = std::copysign(1.0, n.z);
    double a = -1.0 / (s + n.z);
    double b = n.x * n.y * a;
    return {{1.0 + s * n.x * n.x * a, s * b, -s * n.x}, {b, s + n.y * n.y * a, -n.y}, n};
}

inline double ggxD(double NoH, double a2) {
    double f = NoH * NoH * (a2 - 1.0) + 1.0;
    return a2 / (kPi * f * f);
}
inline double lambdaFactor(double c, double a2) {
    return std::sqrt(a2 + (1.0 - a2) * c * c);
}
// Height-correlated Smith visibility G2 / (4 NoL NoV) and masking G1.
inline double smithVisibility(double NoV, double NoL, double a2) {
    return 0.5 / (NoL * lambdaFactor(NoV, a2) + NoV * lambdaFactor(NoL, a2));
}
inline double smithG1(double NoV, double a2) {
    return 2.0 * NoV / (NoV + lambdaFactor(NoV, a2));
}

// Visible normal for a view in the local frame (Heitz 2018, listing 1).
inline glm::dvec3 sampleVisibleNormal(const glm::dvec3& v, double alpha, glm::dvec2 u) {
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

// x^5 by multiplications: std::pow(x, 5.0) is a library call, three of them per BRDF evaluation.
inline double pow5(double x) {
    const double x2 = x * x;
    return x2 * x2 * x;
}

inline double luminance(const glm::dvec3& c) {
    return 0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z;
}

// One shading point's material (renderReference's model): its frame, view, GGX alpha, f0/f90, energy
// compensation and diffuse colour; f(v, l) <n.l> split into specular and diffuse, and the densities of
// the visible-normal and cosine samplers.
struct PointMaterial {
    glm::dvec3 N, V, vLocal;
    Basis frame;
    double NoV, r, alpha, a2, g1;
    glm::dvec3 diffuseColor, f0, compensation{1.0};
    double f90;
    bool specular, diffuse, disney;

    // `albedo(NoV, alpha)`: the directional albedo E of the energy compensation.
    template <class Albedo>
    PointMaterial(const ShadingPoint& sp, const RuntimeOptions& options, double minAlpha, Albedo albedo) {
        auto safeUnit = [](glm::dvec3 v, glm::dvec3 fallback) {
            double l = glm::length(v);
            return l > 1e-30 ? v / l : fallback;
        };
        N = safeUnit(glm::dvec3(sp.normal), {0.0, 1.0, 0.0});
        frame = basisAround(N);
        vLocal = frame.toLocal(safeUnit(glm::dvec3(sp.view), N));
        // A view at or below the horizon is bent up to grazing (NoV = 1e-4), keeping its azimuth.
        if (vLocal.z < 1e-4) {
            double h = std::hypot(vLocal.x, vLocal.y);
            vLocal = h > 0.0 ? glm::dvec3(vLocal.x / h * std::sqrt(1.0 - 1e-8),
                                          vLocal.y / h * std::sqrt(1.0 - 1e-8), 1e-4)
                             : glm::dvec3(0.0, 0.0, 1.0);
        }
        V = frame.toWorld(vLocal);
        NoV = vLocal.z;
        r = std::clamp(double(sp.perceptualRoughness), 0.0, 1.0);
        alpha = std::max(r * r, minAlpha);
        a2 = alpha * alpha;
        const double metallic = std::clamp(double(sp.metallic), 0.0, 1.0);
        const glm::dvec3 base(sp.baseColor);
        diffuseColor = base * (1.0 - metallic);
        f0 = glm::dvec3(double(options.dielectricF0) * (1.0 - metallic)) + base * metallic;
        f90 = options.f90FromF0 ? std::clamp(50.0 * 0.33f * (f0.x + f0.y + f0.z), 0.0, 1.0) : 1.0;
        if (options.energyCompensation && options.specular)
            compensation = 1.0 + f0 * (1.0 / albedo(NoV, alpha) - 1.0);
        g1 = smithG1(NoV, a2);
        specular = options.specular;
        diffuse = options.diffuse;
        disney = options.diffuseModel == DiffuseModel::Disney;
    }

    // The mirror direction of the view, the axis of the specular lobe.
    glm::dvec3 reflected() const { return 2.0 * NoV * N - V; }

    double visibleNormalPdf(const glm::dvec3& l) const {
        glm::dvec3 h = glm::normalize(V + l);
        double NoH = glm::dot(N, h), VoH = glm::dot(V, h);
        return NoH > 0.0 && VoH > 0.0 ? g1 * ggxD(NoH, a2) / (4.0 * NoV) : 0.0;
    }
    glm::dvec3 sampleVisibleNormalDirection(glm::dvec2 u) const {
        glm::dvec3 hl = sampleVisibleNormal(vLocal, alpha, u);
        return frame.toWorld(2.0 * glm::dot(vLocal, hl) * hl - vLocal);
    }
    glm::dvec3 sampleCosineDirection(glm::dvec2 u) const { // Malley
        double rr = std::sqrt(u.x), phi = 2.0 * kPi * u.y;
        return frame.toWorld({rr * std::cos(phi), rr * std::sin(phi), std::sqrt(std::max(0.0, 1.0 - u.x))});
    }

    // f(v, l) <n.l> for unit l with NoL > 0: specular, diffuse (RGB).
    void evaluate(const glm::dvec3& l, double NoL, glm::dvec3& specularOut, glm::dvec3& diffuseOut) const {
        glm::dvec3 h = glm::normalize(V + l);
        double NoH = std::max(glm::dot(N, h), 0.0), LoH = std::clamp(glm::dot(l, h), 0.0, 1.0);
        specularOut = glm::dvec3(0.0), diffuseOut = glm::dvec3(0.0);
        if (specular) {
            double fc = pow5(1.0 - LoH);
            glm::dvec3 F = f0 + (f90 - f0) * fc;
            specularOut = F * compensation * (ggxD(NoH, a2) * smithVisibility(NoV, NoL, a2) * NoL);
        }
        if (diffuse) {
            double fd = 1.0;
            if (disney) {
                const double energyBias = 0.5 * r, energyFactor = 1.0 + (1.0 / 1.51 - 1.0) * r;
                double fd90 = energyBias + 2.0 * LoH * LoH * r;
                double lightScatter = 1.0 + (fd90 - 1.0) * pow5(1.0 - NoL);
                double viewScatter = 1.0 + (fd90 - 1.0) * pow5(1.0 - NoV);
                fd = lightScatter * viewScatter * energyFactor;
            }
            diffuseOut = diffuseColor * (fd / kPi * NoL);
        }
    }
};

} // namespace ibl::reference
