// Diffuse SH time (Google Benchmark; never a pass/fail timer): bakeDiffuseSH on the sample HDRI's cube
// (256-px faces, as `iblbake diffuse` ingests it), and its two steps on their own: the projection of the
// cube onto the 9 coefficients and the automatic window search on the coefficients. Process CPU time is
// reported beside wall time: on a shared 2-core machine it is the steadier figure.
#include "bench_sample.h"

#include <iblbake/baker/sh.h>

#include <benchmark/benchmark.h>

namespace {

void bakeDiffuseSH(benchmark::State& state) {
    const ibl::CubeMap& cube = ibl::bench::sampleCube();
    for (auto _ : state)
        benchmark::DoNotOptimize(ibl::bakeDiffuseSH(cube, ibl::ShWindowSettings{}));
    state.SetLabel(std::to_string(cube.faceSize) + " px faces");
}

void projectRadianceSH(benchmark::State& state) {
    const ibl::CubeMap& cube = ibl::bench::sampleCube();
    for (auto _ : state)
        benchmark::DoNotOptimize(ibl::projectRadianceSH(cube));
}

void chooseShWindow(benchmark::State& state) {
    const ibl::ShRgb radiance = ibl::projectRadianceSH(ibl::bench::sampleCube());
    for (auto _ : state)
        benchmark::DoNotOptimize(ibl::chooseShWindow(radiance, ibl::ShWindowSettings{}));
}

BENCHMARK(bakeDiffuseSH)->Apply(ibl::bench::wallAndCpuMilliseconds);
BENCHMARK(projectRadianceSH)->Apply(ibl::bench::wallAndCpuMilliseconds);
BENCHMARK(chooseShWindow)->Apply(ibl::bench::wallAndCpuMilliseconds);

} // namespace
