// What the benchmarks share: the sample HDRI they time, ingested once per face size, and the units they
// report in.
#pragma once

#include <iblbake/baker/ingest.h>

#include <benchmark/benchmark.h>

#include <map>

namespace ibl::bench {

// The README's sample HDRI (rooitou_park_1k.hdr, a 65,000-nit sun) ingested with n-texel faces (0: the
// face size the ingest picks, as the CLI's commands ingest it).
inline const CubeMap& sampleCube(int faceSize = 0) {
    static std::map<int, CubeMap> cubes;
    auto it = cubes.find(faceSize);
    if (it == cubes.end()) {
        IngestSettings settings;
        settings.sourceFaceSize = faceSize;
        it = cubes.emplace(faceSize, ingestEnvironment({IBLBAKE_SAMPLE_HDRI}, settings).cube).first;
    }
    return it->second;
}

// Milliseconds of wall time, with the process's CPU time beside it: on a shared 2-core machine the CPU
// time is the steadier figure.
inline void wallAndCpuMilliseconds(benchmark::internal::Benchmark* b) {
    b->Unit(benchmark::kMillisecond)->UseRealTime()->MeasureProcessCPUTime();
}

} // namespace ibl::bench
