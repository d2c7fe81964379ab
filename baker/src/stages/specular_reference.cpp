// Brute-force reference of one LD level: every source texel, solid-angle weighted, fp64 accumulation.
// Used by tests and the accuracy report, never by a production path.
#include "iblbake/baker/specular.h"

#include <ld.h>

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

namespace ibl {

CubeMap referenceSpecularLevel(const CubeMap& source, int outputFaceSize, float perceptualRoughness) {
    const int w = source.faceSize, n = outputFaceSize;
    const double alpha = std::max(double(perceptualRoughness) * perceptualRoughness, 1e-6);
    const double a2 = alpha * alpha;
    const std::size_t faceTexels = std::size_t(w) * w;
    std::vector<glm::dvec3> centres(6 * faceTexels);
    for (int f = 0; f < 6; ++f)
        for (int y = 0; y < w; ++y)
            for (int x = 0; x < w; ++x)
                centres[f * faceTexels + std::size_t(y) * w + x] =
                    glm::normalize(glm::dvec3(cubeFaceDirection(f, (x + 0.5f) / w, (y + 0.5f) / w)));
    const double texelAngle =
        std::sqrt(4.0 * 3.14159265358979323846 / (6.0 * faceTexels)); // typical, in radians

    // D(h) NoL over one texel of constant radiance, integrated on an S x S grid of exact sub-texel solid
    // angles. S grows as the lobe gets narrow compared with the texel and the texel near the lobe: D's
    // relative change across a sub-texel is about 4 (size / max(angle, alpha)), kept under ~0.1.
    const float texelSize = 2.0f / float(w);
    auto texelWeight = [&](const glm::dvec3& nrm, int f, int x, int y, double angle) {
        // Within three texels of a lobe under a quarter texel wide, D is too peaked for any grid: the
        // closed-form small-angle integral (kernels/ld.h, checked against quadrature in tests) is exact
        // to O(texel angle^2).
        if (4.0 * alpha < texelSize && angle < 3.0 * texelSize)
            return double(narrowLobeTexelWeight(frameFromNormal(vec3(nrm)), f, -1.0f + x * texelSize,
                                                -1.0f + y * texelSize, texelSize, float(alpha)));
        int S = int(std::clamp(std::ceil(40.0 * texelAngle / std::max(angle, alpha)), 1.0, 256.0));
        double weight = 0.0, step = 2.0 / (double(w) * S);
        for (int j = 0; j < S; ++j)
            for (int i = 0; i < S; ++i) {
                double u0 = -1.0 + (x * S + i) * step, v0 = -1.0 + (y * S + j) * step;
                double omega = cubeAreaElement(float(u0), float(v0)) -
                               cubeAreaElement(float(u0), float(v0 + step)) -
                               cubeAreaElement(float(u0 + step), float(v0)) +
                               cubeAreaElement(float(u0 + step), float(v0 + step));
                if (S == 1) omega = cubeTexelSolidAngle(x, y, w);
                float s = float((x * S + i + 0.5) / (double(w) * S)),
                      t = float((y * S + j + 0.5) / (double(w) * S));
                glm::dvec3 l = glm::normalize(glm::dvec3(cubeFaceDirection(f, s, t)));
                double NoL = glm::dot(nrm, l);
                if (NoL <= 0.0) continue;
                // Expectation of Listing 19's estimator: pdf D(h) / 4 (N = V), weighted by NoL.
                double NoH = glm::dot(nrm, glm::normalize(nrm + l));
                double d = NoH * NoH * (a2 - 1.0) + 1.0;
                weight += a2 / (d * d) * NoL * std::abs(omega);
            }
        return weight;
    };

    CubeMap out(n);
    tbb::parallel_for(0, 6 * n, [&](int row) {
        int face = row / n, y = row % n;
        for (int x = 0; x < n; ++x) {
            glm::dvec3 nrm =
                glm::normalize(glm::dvec3(cubeFaceDirection(face, (x + 0.5f) / n, (y + 0.5f) / n)));
            glm::dvec3 sum(0.0);
            double weightSum = 0.0;
            for (std::size_t k = 0; k < centres.size(); ++k) {
                double cosAngle = glm::dot(nrm, centres[k]);
                if (cosAngle <= -0.1) continue; // entirely below the horizon
                double angle = std::acos(std::clamp(cosAngle, -1.0, 1.0));
                int f = int(k / faceTexels), texel = int(k % faceTexels);
                double weight = texelWeight(nrm, f, texel % w, texel / w, angle);
                sum += weight * glm::dvec3(source.faces[f].pixels[std::size_t(texel)]);
                weightSum += weight;
            }
            out.faces[face].at(x, y) = glm::vec4(glm::vec3(sum / weightSum), 1.0f);
        }
    });
    return out;
}

} // namespace ibl
