// Specular LD chain bake time per backend and preset (Google Benchmark; never a pass/fail timer).
#include "bench_sample.h"

#include <iblbake/baker/specular.h>

#include <benchmark/benchmark.h>

#include <iostream>

namespace {

void bakeChain(benchmark::State& state, ibl::Backend backend) {
    ibl::Executor executor = ibl::Executor::create(backend, "", std::cerr);
    const ibl::CubeMap& source = ibl::bench::sampleCube(int(state.range(0)));
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
