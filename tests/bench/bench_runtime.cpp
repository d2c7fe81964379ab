// Runtime shading time per point (Google Benchmark; never a pass/fail timer): evaluateCpu (TBB, the CPU
// backend) on 65,536 points of the sample HDRI's distant probe (256-px LD chain with its rough layers, DFG
// LUT, SH), normals over the sphere, perceptual roughness spread over [0, 1], the distant LD read once (the
// split sum's lookup) or from the fitted taps (kernels/specular_taps.h); the specular term alone, and the
// whole shading (specular and diffuse). Process CPU time is reported beside wall time: on a shared 2-core
// machine it is the steadier figure.
#include "bench_sample.h"

#include <iblbake/baker/dfg_lut.h>
#include <iblbake/baker/sh.h>
#include <iblbake/baker/specular.h>
#include <iblbake/runtime/runtime.h>

#include <benchmark/benchmark.h>

#include <cmath>
#include <vector>

namespace {

constexpr std::size_t kPoints = 65536;

const ibl::ProbeSet& sampleProbe() {
    static const ibl::ProbeSet set = [] {
        const ibl::CubeMap& cube = ibl::bench::sampleCube(256);
        const ibl::Executor executor = ibl::Executor::cpu();
        ibl::SpecularWithRoughLayers ld =
            ibl::bakeSpecularWithRoughLayers(cube, ibl::SpecularSettings{}, executor);
        ibl::ProbeSet probe(
            ibl::ldPyramidFromChain(ld.chain, ibl::MipMapping::Frostbite),
            ibl::dfgTableFromImage(ibl::bakeDfgLut(ibl::DfgSettings{}, executor)),
            ibl::shCoefficientsFrom(ibl::bakeDiffuseSH(cube, ibl::ShWindowSettings{}).irradiance, false));
        probe.setRoughLayers(ld.roughLayers);
        return probe;
    }();
    return set;
}

// Points on a Fibonacci sphere seen from +Z (points facing away see it at grazing angles too), roughness
// cycling through [0, 1].
const std::vector<ibl::ShadingPoint>& samplePoints() {
    static const std::vector<ibl::ShadingPoint> points = [] {
        std::vector<ibl::ShadingPoint> out(kPoints);
        for (std::size_t i = 0; i < kPoints; ++i) {
            const float z = 1.0f - 2.0f * (float(i) + 0.5f) / float(kPoints), rho = std::sqrt(1.0f - z * z);
            const float phi = 2.39996323f * float(i);
            ibl::ShadingPoint& p = out[i];
            p.position = glm::vec3(0.0f);
            p.normal = glm::vec3(rho * std::cos(phi), rho * std::sin(phi), z);
            p.view = glm::vec3(0.0f, 0.0f, 1.0f);
            p.baseColor = glm::vec3(0.9f, 0.6f, 0.5f);
            p.metallic = float(i % 2);
            p.perceptualRoughness = float(i % 101) / 100.0f;
            p.ao = 1.0f;
        }
        return out;
    }();
    return points;
}

// range(0): taps on; range(1): diffuse on as well.
void shadePoints(benchmark::State& state) {
    ibl::RuntimeOptions options;
    options.specularTaps = state.range(0) != 0;
    options.diffuse = state.range(1) != 0;
    const ibl::ProbeSet& set = sampleProbe();
    const std::vector<ibl::ShadingPoint>& points = samplePoints();
    for (auto _ : state)
        benchmark::DoNotOptimize(ibl::evaluateCpu(set, points, options));
    state.counters["ns/point"] = benchmark::Counter(
        double(kPoints), benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
    state.SetLabel(std::string(options.specularTaps ? "taps" : "single read") +
                   (options.diffuse ? ", specular + diffuse" : ", specular"));
}

} // namespace

BENCHMARK(shadePoints)->ArgsProduct({{0, 1}, {0, 1}})->Apply(ibl::bench::wallAndCpuMilliseconds);
