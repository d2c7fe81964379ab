// The benchmarks run under the allocator policy of the processes they stand for (process_memory.h): without
// it, whether a freed block is faulted in again depends on which benchmarks ran before.
#include <iblbake/baker/process_memory.h>

#include <benchmark/benchmark.h>

int main(int argc, char** argv) {
    ibl::reuseFreedBlocks();
    benchmark::Initialize(&argc, argv);
    if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
    benchmark::RunSpecifiedBenchmarks();
    benchmark::Shutdown();
    return 0;
}
