// Diffuse SH time (Google Benchmark; never a pass/fail timer): bakeDiffuseSH on the sample HDRI's cube
// (256-px faces, as `iblbake diffuse` ingests it), and its two steps on their own: the projection of the
// cube onto the 9 coefficients and the automatic window search on the coefficients. Process CPU time is
// reported beside wall time: on a shared 2-core machine it is the steadier figure.
#include <iblbake/baker/ingest.h>
#include <iblbake/baker/sh.h>

#include <benchmark/benchmark.h>

namespace {

const ibl::CubeMap& sampleCube() {
    static const ibl::CubeMap cube = ibl::ingestEnvironment({IBLBAKE_SAMPLE_HDRI}, {}).cube;
    return cube;
}

void bakeDiffuseSH(benchmark::State& state) {
    const ibl::CubeMap& cube = sampleCube();
    for (auto _ : state)
        benchmark::DoNotOptimize(ibl::bakeDiffuseSH(cube, ibl::ShWindowSettings{}));
    state.SetLabel(std::to_string(cube.faceSize) + " px faces");
}

void projectRadianceSH(benchmark::State& state) {
    const ibl::CubeMap& cube = sampleCube();
    for (auto _ : state)
        benchmark::DoNotOptimize(ibl::projectRadianceSH(cube));
}

void chooseShWindow(benchmark::State& state) {
    const ibl::ShRgb radiance = ibl::projectRadianceSH(sampleCube());
    for (auto _ : state)
        benchmark::DoNotOptimize(ibl::chooseShWindow(radiance, ibl::ShWindowSettings{}));
}

void timed(benchmark::internal::Benchmark* b) {
    b->Unit(benchmark::kMillisecond)->UseRealTime()->MeasureProcessCPUTime();
}

BENCHMARK(bakeDiffuseSH)->Apply(timed);
BENCHMARK(projectRadianceSH)->Apply(timed);
BENCHMARK(chooseShWindow)->Apply(timed);

} // namespace
