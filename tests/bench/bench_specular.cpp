// Specular LD chain bake time per backend and preset (Google Benchmark; never a pass/fail timer).
#include "bench_sample.h"

#include <iblbake/baker/specular.h>

#include <benchmark/benchmark.h>

#include <iostream>
#include <string>
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

// The kernel time of each level of one chain from its dispatches in order (a level's first dispatch is
// ldLevel or ldOnePass, its ldBright follows), and the ldBright part of it.
struct LevelKernelMs {
    std::vector<double> all, bright;
};
LevelKernelMs kernelMsPerLevel(const std::vector<ibl::ocl::DispatchTiming>& dispatches) {
    LevelKernelMs levels;
    for (const ibl::ocl::DispatchTiming& d : dispatches) {
        const bool bright = d.kernel == "ldBright" && !levels.all.empty();
        if (!bright) {
            levels.all.push_back(0.0);
            levels.bright.push_back(0.0);
        }
        levels.all.back() += d.milliseconds;
        if (bright) levels.bright.back() += d.milliseconds;
    }
    return levels;
}

// Adds one chain's per-level values to the sums over the iterations.
void addPerLevel(std::vector<double>& sums, const std::vector<double>& values) {
    sums.resize(values.size());
    for (std::size_t k = 0; k < values.size(); ++k)
        sums[k] += values[k];
}

// The production chain's levels one by one (issue 18: OpenCL at least as fast as the CPU backend at every
// level), means over the iterations in ms: L1.. each level's time as the bake measures it (from the previous
// level's end to its own: table, upload, kernels, read-back, which OpenCL overlaps with the next level's
// table), K1.. its kernels' time (OpenCL: device time from profiling events; CPU: the
// dispatches' wall time), B1.. the bright pass's part of K.
void bakeChainLevels(benchmark::State& state, ibl::Backend backend) {
    ibl::Executor executor = ibl::Executor::create(backend, "", std::cerr);
    const ibl::CubeMap& source = ibl::bench::sampleCube(int(state.range(0)));
    const ibl::SpecularSettings settings;
    ibl::bakeSpecular(source, settings, executor); // program build outside the timed loop
    executor.takeTimings();
    std::vector<double> levelMs, kernelMs, brightMs;
    for (auto _ : state) {
        std::vector<ibl::SpecularLevelTiming> timings;
        benchmark::DoNotOptimize(ibl::bakeSpecular(source, settings, executor, &timings));
        levelMs.resize(timings.size());
        for (std::size_t k = 0; k < timings.size(); ++k)
            levelMs[k] += timings[k].milliseconds;
        const LevelKernelMs kernels = kernelMsPerLevel(executor.takeTimings());
        addPerLevel(kernelMs, kernels.all);
        addPerLevel(brightMs, kernels.bright);
    }
    const auto report = [&](const char* prefix, const std::vector<double>& ms) {
        for (std::size_t k = 0; k < ms.size(); ++k)
            state.counters[prefix + std::to_string(k + 1)] = ms[k] / double(state.iterations());
    };
    report("L", levelMs);
    report("K", kernelMs);
    report("B", brightMs);
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
