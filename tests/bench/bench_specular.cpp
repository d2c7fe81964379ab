// Specular LD chain bake time per backend and preset (Google Benchmark; never a pass/fail timer).
#include <iblbake/baker/ingest.h>
#include <iblbake/baker/specular.h>

#include <benchmark/benchmark.h>

#include <iostream>

namespace {

// The README's sample HDRI (rooitou_park_1k.hdr, a 65,000-nit sun) at n-texel faces.
ibl::CubeMap sampleCube(int n) {
    ibl::IngestSettings settings;
    settings.sourceFaceSize = n;
    return ibl::ingestEnvironment({IBLBAKE_SAMPLE_HDRI}, settings).cube;
}

void bakeChain(benchmark::State& state, ibl::Backend backend) {
    ibl::Executor executor = ibl::Executor::create(backend, "", std::cerr);
    ibl::CubeMap source = sampleCube(int(state.range(0)));
    ibl::SpecularSettings settings;
    settings.samples = std::uint32_t(state.range(1));
    ibl::bakeSpecular(source, settings, executor); // program build outside the timed loop
    for (auto _ : state)
        benchmark::DoNotOptimize(ibl::bakeSpecular(source, settings, executor));
    state.SetLabel(executor.description());
}

BENCHMARK_CAPTURE(bakeChain, opencl, ibl::Backend::OpenCL)
    ->Args({256, 32})
    ->Args({256, 256})
    ->Args({256, 1024})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK_CAPTURE(bakeChain, cpu, ibl::Backend::Cpu)
    ->Args({256, 256})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

} // namespace
