#include "iblbake/dfg_lut.h"
#include "iblbake/error.h"

#include <dfg.h>

#include <tbb/parallel_for.h>

#include <algorithm>
#include <string>
#include <vector>

namespace ibl {
namespace {

static_assert(sizeof(DfgParams) == 12 && offsetof(DfgParams, endSample) == 8, "DfgParams must match dfg.cl");

std::vector<float4> sampleTable(std::uint32_t sampleCount) {
    std::vector<float4> table(sampleCount);
    for (std::uint32_t i = 0; i < sampleCount; ++i)
        table[i] = dfgSampleEntry(i, sampleCount);
    return table;
}

// Sums of (DFG1, DFG2, Disney) per texel, in RGB; the caller divides by the sample count.
ImageRGBA sumsCpu(const DfgSettings& s, const std::vector<float4>& table) {
    ImageRGBA sums(int(s.size), int(s.size));
    tbb::parallel_for(std::uint32_t(0), s.size, [&](std::uint32_t y) {
        for (std::uint32_t x = 0; x < s.size; ++x) {
            glm::vec3 total(0.0f);
            for (std::uint32_t first = 0; first < s.sampleCount; first += kDfgChunkSamples)
                total += integrateDfgChunk(dfgTexelCenter(x, s.size), dfgTexelCenter(y, s.size), &table[0].x,
                                           first, std::min(s.sampleCount, first + kDfgChunkSamples));
            sums.at(int(x), int(y)) = float4(total, 0.0f);
        }
    });
    return sums;
}

ImageRGBA sumsOpenCL(const DfgSettings& s, const std::vector<float4>& table, ocl::Context& cl) {
    ImageRGBA sums(int(s.size), int(s.size));
    const std::size_t bytes = sums.pixels.size() * sizeof(float4);
    cl::Kernel kernel = cl.kernel("dfg.cl", "dfgLutChunk");
    cl::Kernel add = cl.kernel("dfg.cl", "addChunk");
    cl::Buffer tableBuffer = cl.upload(table);
    cl::Buffer chunkBuffer = cl.createBuffer(CL_MEM_READ_WRITE, bytes);
    cl::Buffer sumsBuffer =
        cl.createBuffer(CL_MEM_READ_WRITE | CL_MEM_COPY_HOST_PTR, bytes, sums.pixels.data());
    kernel.setArg(1, tableBuffer);
    kernel.setArg(2, chunkBuffer);
    add.setArg(0, chunkBuffer);
    add.setArg(1, sumsBuffer);
    const bool singleChunk = s.sampleCount <= kDfgChunkSamples;
    if (singleChunk) kernel.setArg(2, sumsBuffer);
    // Rows of 32 texels share a roughness, so the work-items of a group run the same loop; PoCL
    // vectorizes across them (see kernels/portable.h).
    const std::uint32_t groupWidth = 32;
    const std::uint32_t paddedWidth = (s.size + groupWidth - 1) / groupWidth * groupWidth;
    for (std::uint32_t first = 0; first < s.sampleCount; first += kDfgChunkSamples) {
        DfgParams params{s.size, first, std::min(s.sampleCount, first + kDfgChunkSamples)};
        kernel.setArg(0, params);
        cl.run(kernel, cl::NDRange(paddedWidth, s.size), cl::NDRange(groupWidth, 1));
        if (!singleChunk) cl.run(add, cl::NDRange(std::size_t(s.size) * s.size));
    }
    cl.download(sumsBuffer, bytes, sums.pixels.data());
    return sums;
}

} // namespace

void validate(const DfgSettings& s) {
    if (s.size == 0 || s.size > 8192)
        throw SettingError("dfgSize", "the LUT size " + std::to_string(s.size) + " is outside 1..8192");
    if (s.sampleCount == 0 || s.sampleCount > (1u << 24))
        throw SettingError("dfgSamples",
                           "the sample count " + std::to_string(s.sampleCount) + " is outside 1..16777216");
}

ImageRGBA bakeDfgLut(const DfgSettings& settings, const Executor& executor) {
    validate(settings);
    std::vector<float4> table = sampleTable(settings.sampleCount);
    ImageRGBA lut =
        executor.usesOpenCL() ? sumsOpenCL(settings, table, executor.cl()) : sumsCpu(settings, table);
    const float inv = 1.0f / float(settings.sampleCount);
    for (glm::vec4& p : lut.pixels)
        p = glm::vec4(glm::vec3(p) * inv, 1.0f);
    return lut;
}

} // namespace ibl
