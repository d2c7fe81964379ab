// DFG LUT bake time per backend (Google Benchmark; never a pass/fail timer).
#include <iblbake/baker/dfg_lut.h>

#include <benchmark/benchmark.h>

#include <iostream>

namespace {

void bakeLut(benchmark::State& state, ibl::Backend backend) {
    ibl::Executor executor = ibl::Executor::create(backend, "", std::cerr);
    ibl::DfgSettings settings;
    settings.size = unsigned(state.range(0));
    settings.sampleCount = unsigned(state.range(1));
    ibl::bakeDfgLut(settings, executor); // builds and caches the program outside the timed loop
    for (auto _ : state)
        benchmark::DoNotOptimize(ibl::bakeDfgLut(settings, executor));
    state.SetLabel(executor.description());
    state.counters["samples/s"] =
        benchmark::Counter(double(settings.size) * settings.size * settings.sampleCount,
                           benchmark::Counter::kIsIterationInvariantRate);
}

BENCHMARK_CAPTURE(bakeLut, opencl, ibl::Backend::OpenCL)
    ->Args({128, 1024})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK_CAPTURE(bakeLut, cpu, ibl::Backend::Cpu)
    ->Args({128, 1024})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

} // namespace
