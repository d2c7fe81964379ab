// Ingest time (Google Benchmark; never a pass/fail timer): the whole ingest of the sample HDRI (read,
// repair, colour, exact-area lat-long -> cube resampling) at n-texel faces.
#include <iblbake/baker/ingest.h>

#include <benchmark/benchmark.h>

namespace {

void ingestSample(benchmark::State& state) {
    ibl::IngestSettings settings;
    settings.sourceFaceSize = int(state.range(0));
    for (auto _ : state)
        benchmark::DoNotOptimize(ibl::ingestEnvironment({IBLBAKE_SAMPLE_HDRI}, settings));
}

BENCHMARK(ingestSample)->Arg(64)->Arg(256)->Arg(1024)->Unit(benchmark::kMillisecond)->UseRealTime();

} // namespace
