// The DFG / diffuse LUT stage (DESIGN.md "DFG LUT"): environment-independent, baked once per settings.
#pragma once

#include "iblbake/core/image.h"
#include "iblbake/opencl/executor.h"

#include <cstdint>

namespace ibl {

struct DfgSettings {
    std::uint32_t size = 128;         // N: texels per side
    std::uint32_t sampleCount = 1024; // samples per texel (specular and diffuse each)
};

// Throws ibl::Error for a size or sample count of zero or beyond 8192 / 2^24.
void validate(const DfgSettings& settings);

// Returns the N x N LUT: R = DFG1, G = DFG2, B = renormalized Disney diffuse, A = 1.
// Row y (first scanline first) holds perceptual roughness (y + 0.5) / N, column x holds NoV = (x + 0.5) / N.
ImageRGBA bakeDfgLut(const DfgSettings& settings, const Executor& executor);

} // namespace ibl
