// Shared helpers of the runtime tests: synthetic environments, SH projection, the baked products a probe
// set needs, and the comparison of the OpenCL and CPU paths.
#pragma once

#include <iblbake/baker/dfg_lut.h>
#include <iblbake/baker/irradiance.h>
#include <iblbake/baker/specular.h>
#include <iblbake/opencl/executor.h>
#include <iblbake/runtime/runtime.h>
#include <iblbake/runtime/runtime_reference.h>

#include <cube.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <span>
#include <sstream>

namespace rt_test {

using namespace ibl;

inline Executor openclOrCpu() {
    std::ostringstream warnings;
    return Executor::create(Backend::Auto, "", warnings);
}

// A cube whose texel (x, y) of face f holds radiance(unit centre direction), averaged over s x s
// sub-texel directions when supersample > 1.
template <class F>
CubeMap makeCube(int n, F radiance, int supersample = 1) {
    CubeMap c(n);
    for (int f = 0; f < 6; ++f)
        for (int y = 0; y < n; ++y)
            for (int x = 0; x < n; ++x) {
                glm::vec3 sum(0.0f);
                for (int j = 0; j < supersample; ++j)
                    for (int i = 0; i < supersample; ++i) {
                        float s = (x + (i + 0.5f) / supersample) / n, t = (y + (j + 0.5f) / supersample) / n;
                        sum += radiance(glm::normalize(glm::vec3(cubeFaceDirection(f, s, t))));
                    }
                c.faces[f].at(x, y) = glm::vec4(sum / float(supersample * supersample), 1.0f);
            }
    return c;
}

// A sky-like environment (the one of test_specular.cpp): gradient sky, warm bright lobe, dark ground.
inline glm::vec3 skyLike(glm::vec3 d) {
    glm::vec3 sky = glm::vec3(0.4f, 0.6f, 1.0f) * (0.5f + 0.5f * std::max(d.y, 0.0f));
    glm::vec3 ground = glm::vec3(0.1f, 0.08f, 0.05f);
    float lobe = std::pow(std::max(glm::dot(d, glm::normalize(glm::vec3(0.5f, 0.4f, 0.6f))), 0.0f), 32.0f);
    return (d.y > 0 ? sky : ground) + glm::vec3(20.0f, 15.0f, 10.0f) * lobe;
}

// Pre-scaled L2 irradiance: radiance projection over every texel (exact solid angles, fp64), clamped-cosine
// convolution A_l and Filament's basis pre-scaling k_i, so that irradianceSH(n) = E(n). (The same math as
// the baker's SH stage; written here so that the runtime tests do not depend on its progress.)
inline ShCoefficients projectIrradianceSH(const CubeMap& cube) {
    const double k[9] = {0.28209479177387814, 0.48860251190291992, 0.48860251190291992,
                         0.48860251190291992, 1.09254843059207907, 1.09254843059207907,
                         0.31539156525252001, 1.09254843059207907, 0.54627421529603954};
    const double pi = 3.14159265358979323846;
    const double A[9] = {pi, 2 * pi / 3, 2 * pi / 3, 2 * pi / 3, pi / 4, pi / 4, pi / 4, pi / 4, pi / 4};
    std::array<glm::dvec3, 9> L{};
    const int n = cube.faceSize;
    for (int f = 0; f < 6; ++f)
        for (int y = 0; y < n; ++y)
            for (int x = 0; x < n; ++x) {
                glm::dvec3 d =
                    glm::normalize(glm::dvec3(cubeFaceDirection(f, (x + 0.5f) / n, (y + 0.5f) / n)));
                double inv = 2.0 / n;
                double x0 = x * inv - 1.0, x1 = x0 + inv, y0 = y * inv - 1.0, y1 = y0 + inv;
                auto area = [](double a, double b) {
                    return std::atan2(a * b, std::sqrt(a * a + b * b + 1.0));
                };
                double omega = std::abs(area(x0, y0) - area(x0, y1) - area(x1, y0) + area(x1, y1));
                double p[9] = {1.0,
                               d.y,
                               d.z,
                               d.x,
                               d.x * d.y,
                               d.y * d.z,
                               3.0 * d.z * d.z - 1.0,
                               d.x * d.z,
                               d.x * d.x - d.y * d.y};
                glm::dvec3 radiance(cube.faces[f].at(x, y));
                for (int i = 0; i < 9; ++i)
                    L[i] += radiance * (k[i] * p[i] * omega);
            }
    ShCoefficients sh;
    for (int i = 0; i < 9; ++i)
        sh.c[i] = glm::vec3(L[i] * (A[i] * k[i]));
    return sh;
}

// The DFG LUT at the default settings (128^2, 1024 samples), baked once per process.
inline const ImageRGBA& dfgLut() {
    static const ImageRGBA lut = bakeDfgLut(DfgSettings{}, openclOrCpu());
    return lut;
}

// LD chain (production preset, Frostbite mapping) of a cube.
inline LdPyramid bakeLd(const CubeMap& cube) {
    static Executor executor = openclOrCpu();
    return ldPyramidFromChain(bakeSpecular(cube, SpecularSettings{}, executor), MipMapping::Frostbite);
}

// A distant-only probe set for an environment cube (LD + DFG + SH), with the baker's irradiance cube
// (production settings, 32-px faces) for the diffuse when asked.
inline ProbeSet distantSet(const CubeMap& cube, bool irradianceCube = false) {
    ProbeSet set(bakeLd(cube), dfgTableFromImage(dfgLut()), projectIrradianceSH(cube));
    if (irradianceCube) {
        static Executor executor = openclOrCpu();
        set.setIrradianceCube(bakeIrradianceCube(cube, IrradianceSettings{}, executor));
    }
    return set;
}

// The probe set of a bake with the sun extracted: residual LD chain whose level 0 keeps the sun (the full
// cube, LdPyramid::sunInLevel0), SH and irradiance cube of the residual, the disk light.
inline ProbeSet distantSetWithSun(const CubeMap& full, const CubeMap& residual, const SunDisk& sun) {
    static Executor executor = openclOrCpu();
    CubeMapChain chain = bakeSpecular(residual, SpecularSettings{}, executor);
    const bool sunInLevel0 = keepSunInLevel0(chain, full, Ktx2Format::RGBA32F);
    LdPyramid ld = ldPyramidFromChain(chain, MipMapping::Frostbite);
    ld.sunInLevel0 = sunInLevel0;
    ProbeSet set(std::move(ld), dfgTableFromImage(dfgLut()), projectIrradianceSH(residual));
    set.setIrradianceCube(bakeIrradianceCube(residual, IrradianceSettings{}, executor));
    set.setSun(sun);
    return set;
}

// Relative mean absolute error of runtime results against the reference's: sum |runtime - reference| /
// sum |reference| over the points and RGB.
inline double relativeError(std::span<const glm::vec4> runtime, std::span<const ReferenceResult> reference) {
    double err = 0.0, sum = 0.0;
    for (std::size_t i = 0; i < runtime.size(); ++i) {
        const glm::dvec3 ref = reference[i].total();
        for (int c = 0; c < 3; ++c) {
            err += std::abs(double(runtime[i][c]) - ref[c]);
            sum += std::abs(ref[c]);
        }
    }
    return err / sum;
}

inline double relativeDifference(const glm::vec4& a, const glm::vec4& b, float floor) {
    double m = 0.0;
    for (int c = 0; c < 3; ++c)
        m = std::max(m, std::abs(double(a[c]) - b[c]) / std::max({std::abs(double(b[c])), double(floor)}));
    return m + std::abs(double(a.w) - b.w);
}

// OpenCL vs CPU on every point: max over points and channels of |cl - cpu| / max(|cpu|, floor) (+ the alpha
// difference). Returns -1 without an OpenCL device.
inline double backendDifference(const ProbeSet& set, std::span<const ShadingPoint> points,
                                const RuntimeOptions& options, float floor = 1e-3f) {
    static Executor executor = openclOrCpu();
    if (!executor.usesOpenCL()) return -1.0;
    OpenCLProbeEvaluator cl(executor.cl(), set);
    std::vector<glm::vec4> gpu = cl.evaluate(points, options);
    std::vector<glm::vec4> cpu = evaluateCpu(set, points, options);
    double worst = 0.0;
    for (std::size_t i = 0; i < points.size(); ++i)
        worst = std::max(worst, relativeDifference(gpu[i], cpu[i], floor));
    return worst;
}

// Stated tolerance of OpenCL vs CPU, relative per channel (to max(|cpu|, 1e-3)): the same functions, but
// the OpenCL compiler contracts a * b + c into FMAs and has its own sqrt/pow/sin, so results differ in the
// last bits, amplified where the result is ill-conditioned: a sun reflected by a view below the horizon
// (NoV clamped to 1e-4) differs by up to ~3e-4; typical points by ~1e-7.
constexpr double kBackendTolerance = 1e-3;

#define EXPECT_BACKENDS_AGREE(set, points, options)                                                          \
    do {                                                                                                     \
        double difference_ = rt_test::backendDifference(set, points, options);                               \
        if (difference_ >= 0.0) {                                                                            \
            std::printf("OpenCL vs CPU: max relative difference %.3g over %zu points\n", difference_,        \
                        std::size(points));                                                                  \
            EXPECT_LT(difference_, rt_test::kBackendTolerance);                                              \
        }                                                                                                    \
    } while (0)

} // namespace rt_test
