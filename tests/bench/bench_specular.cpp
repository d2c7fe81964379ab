// Specular LD chain bake time per backend and preset (Google Benchmark; never a pass/fail timer).
#include "bench_sample.h"

#include <iblbake/baker/specular.h>

#include <benchmark/benchmark.h>

#include <cstdio>
#include <iostream>
#include <vector>

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

// The production chain's levels one by one (issue 18: OpenCL at least as fast as the CPU backend at every
// level): each level's time as the bake measures it (table, upload, kernels, read-back), mean over the
// iterations, as counters L1.. in ms.
void bakeChainLevels(benchmark::State& state, ibl::Backend backend) {
    ibl::Executor executor = ibl::Executor::create(backend, "", std::cerr);
    const ibl::CubeMap& source = ibl::bench::sampleCube(int(state.range(0)));
    const ibl::SpecularSettings settings;
    ibl::bakeSpecular(source, settings, executor); // program build outside the timed loop
    std::vector<double> levelMs;
    for (auto _ : state) {
        std::vector<ibl::SpecularLevelTiming> timings;
        benchmark::DoNotOptimize(ibl::bakeSpecular(source, settings, executor, &timings));
        levelMs.resize(timings.size());
        for (std::size_t k = 0; k < timings.size(); ++k)
            levelMs[k] += timings[k].milliseconds;
    }
    for (std::size_t k = 0; k < levelMs.size(); ++k) {
        char name[24];
        std::snprintf(name, sizeof name, "L%zu", k + 1);
        state.counters[name] = levelMs[k] / double(state.iterations());
    }
    state.SetLabel(executor.description());
}

BENCHMARK_CAPTURE(bakeChainLevels, opencl, ibl::Backend::OpenCL)
    ->Arg(256)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK_CAPTURE(bakeChainLevels, cpu, ibl::Backend::Cpu)
    ->Arg(256)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

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
