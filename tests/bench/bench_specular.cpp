// Specular LD chain bake time per backend and preset (Google Benchmark; never a pass/fail timer).
#include <iblbake/specular.h>

#include <cube.h>

#include <benchmark/benchmark.h>

#include <cmath>
#include <iostream>

namespace {

ibl::CubeMap skyCube(int n) {
    ibl::CubeMap c(n);
    for (int f = 0; f < 6; ++f)
        for (int y = 0; y < n; ++y)
            for (int x = 0; x < n; ++x) {
                glm::vec3 d = glm::normalize(ibl::cubeFaceDirection(f, (x + 0.5f) / n, (y + 0.5f) / n));
                float sun = std::pow(std::max(glm::dot(d, glm::normalize(glm::vec3(0.3f, 0.5f, 0.8f))), 0.0f),
                                     2000.0f);
                c.faces[f].at(x, y) = glm::vec4(glm::vec3(0.5f + 0.5f * d.y) + glm::vec3(5e4f * sun), 1.0f);
            }
    return c;
}

void bakeChain(benchmark::State& state, ibl::Backend backend) {
    ibl::Executor executor = ibl::Executor::create(backend, "", std::cerr);
    ibl::CubeMap source = skyCube(int(state.range(0)));
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
