#include "iblbake/baker/dfg_lut.h"
#include "iblbake/core/error.h"
#include "iblbake/opencl/dispatch.h"

#include "host_clones.h"

#include <dfg.h>

#include <algorithm>
#include <string>
#include <vector>

namespace ibl {
namespace {

static_assert(sizeof(DfgParams) == 12 && offsetof(DfgParams, endSample) == 8, "DfgParams must match dfg.cl");

std::vector<float> sampleTable(std::uint32_t sampleCount) {
    std::vector<float> table;
    table.reserve(std::size_t(sampleCount) * IBL_DFG_SAMPLE_FLOATS);
    for (std::uint32_t i = 0; i < sampleCount; ++i) {
        float4 e = dfgSampleEntry(i, sampleCount);
        table.insert(table.end(), {e.x, e.y, e.z, e.w});
    }
    return table;
}

// The CPU backend's item (dfg.h's dfgChunkItem inlined), compiled for each of these instruction sets and
// chosen at load time: the sample loop vectorizes across samples (IBL_SIMD_SUM) as wide as the machine
// allows while the program stays portable x86-64 (bench_iblbake bakeLut/cpu, 128^2 texels x 1024 samples:
// 8-10x the scalar loop with AVX2). The sums' lanes follow the vector width, so the LUT's last bits
// depend on the clone chosen (a few 1e-6 at most, tests/test_dfg.cpp OpenCLAgreesWithCpu).
IBL_HOST_CLONES void dfgChunkItemHost(WorkItem t, float* out, DfgParams params, const float* table) {
    dfgChunkItem(t, out, params, table);
}

} // namespace

Backend standaloneDfgBackend(Backend requested, bool deviceNamed) {
    return requested == Backend::Auto && !deviceNamed ? Backend::Cpu : requested;
}

void validate(const DfgSettings& s) {
    if (s.size == 0 || s.size > 8192)
        throw SettingError("dfgSize", "the LUT size " + std::to_string(s.size) + " is outside 1..8192");
    if (s.sampleCount == 0 || s.sampleCount > (1u << 24))
        throw SettingError("dfgSamples",
                           "the sample count " + std::to_string(s.sampleCount) + " is outside 1..16777216");
}

ImageRGBA bakeDfgLut(const DfgSettings& settings, const Executor& executor) {
    validate(settings);
    const std::vector<float> table = sampleTable(settings.sampleCount);
    // Sums of (DFG1, DFG2, Disney) per texel, chunk by chunk (dfg.h), then divided by the sample count.
    const Dispatcher dispatcher(executor);
    const DispatchGrid grid = DispatchGrid::image(settings.size, settings.size);
    const DeviceArray<float> samples = dispatcher.upload("DFG sample table", table);
    const auto chunkKernel = kernel("dfg.cl", "dfgLutChunk", dfgChunkItemHost);
    auto chunkParams = [&](std::uint32_t first) {
        return DfgParams{settings.size, first, std::min(settings.sampleCount, first + kDfgChunkSamples)};
    };
    DispatchOutput sums = dispatcher.output(grid);
    dispatcher.run(chunkKernel, sums, chunkParams(0), samples);
    if (settings.sampleCount > kDfgChunkSamples) {
        DispatchOutput chunk = dispatcher.output(grid);
        for (std::uint32_t first = kDfgChunkSamples; first < settings.sampleCount;
             first += kDfgChunkSamples) {
            dispatcher.run(chunkKernel, chunk, chunkParams(first), samples);
            dispatcher.run(kernel("dfg.cl", "addChunk", dfgAddChunkItem), sums, chunkParams(first),
                           chunk.asInput());
        }
    }
    ImageRGBA lut = dispatcher.downloadImage(sums);
    const float inv = 1.0f / float(settings.sampleCount);
    for (glm::vec4& p : lut.pixels)
        p = glm::vec4(glm::vec3(p) * inv, 1.0f);
    return lut;
}

} // namespace ibl
