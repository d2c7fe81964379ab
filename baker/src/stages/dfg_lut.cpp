#include "iblbake/dfg_lut.h"
#include "iblbake/error.h"

#include <dfg.h>

#include <tbb/parallel_for.h>

#include <string>
#include <vector>

namespace ibl {
namespace {

static_assert(sizeof(DfgParams) == 8 && offsetof(DfgParams, sampleCount) == 4, "DfgParams must match dfg.cl");

std::vector<float4> sampleTable(std::uint32_t sampleCount) {
    std::vector<float4> table(sampleCount);
    for (std::uint32_t i = 0; i < sampleCount; ++i) table[i] = dfgSampleEntry(i, sampleCount);
    return table;
}

ImageRGBA bakeCpu(const DfgSettings& s, const std::vector<float4>& table) {
    ImageRGBA lut(int(s.size), int(s.size));
    tbb::parallel_for(std::uint32_t(0), s.size, [&](std::uint32_t y) {
        for (std::uint32_t x = 0; x < s.size; ++x) {
            vec3 dfg = integrateDfg(dfgTexelCenter(x, s.size), dfgTexelCenter(y, s.size), &table[0].x,
                                      s.sampleCount);
            lut.at(int(x), int(y)) = float4(dfg, 1.0f);
        }
    });
    return lut;
}

ImageRGBA bakeOpenCL(const DfgSettings& s, const std::vector<float4>& table, ocl::Context& cl) {
    ImageRGBA lut(int(s.size), int(s.size));
    cl::Kernel kernel = cl.kernel("dfg.cl", "dfgLut");
    cl::Buffer tableBuffer = cl.upload(table);
    cl::Buffer out = cl.createBuffer(CL_MEM_WRITE_ONLY, lut.pixels.size() * sizeof(float4));
    DfgParams params{s.size, s.sampleCount};
    kernel.setArg(0, params);
    kernel.setArg(1, tableBuffer);
    kernel.setArg(2, out);
    // Rows of 16 texels share a roughness, so work-items of a group run the same loop trip count.
    std::uint32_t padded = (s.size + 63u) / 64u * 64u;
    cl.run(kernel, cl::NDRange(padded, s.size), cl::NDRange(64, 1));
    cl.download(out, lut.pixels.size() * sizeof(float4), lut.pixels.data());
    return lut;
}

} // namespace

void validate(const DfgSettings& s) {
    if (s.size == 0 || s.size > 8192)
        throw Error("--size: " + std::to_string(s.size) + " is outside 1..8192");
    if (s.sampleCount == 0 || s.sampleCount > (1u << 24))
        throw Error("--samples: " + std::to_string(s.sampleCount) + " is outside 1..16777216");
}

ImageRGBA bakeDfgLut(const DfgSettings& settings, const Executor& executor) {
    validate(settings);
    std::vector<float4> table = sampleTable(settings.sampleCount);
    return executor.usesOpenCL() ? bakeOpenCL(settings, table, executor.cl()) : bakeCpu(settings, table);
}

} // namespace ibl
