// The DFG / diffuse LUT stage (docs/conventions.md "DFG LUT layout"): environment-independent, baked once per
// settings.
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

// The backend that `auto` means for a process whose only stage is the LUT (`iblbake dfg`): the CPU
// backend, unless a device was named. OpenCL's set-up before a first kernel (the platform query alone loads
// the driver: PoCL with LLVM, 0.07-0.09 s of CPU, then a context and the program) costs more than the whole
// default LUT on the CPU backend (57 ms of CPU for 128^2 x 1024 samples, vectorized), and a stage that
// short cannot win it back on any device. A process that already has a backend (a scene bake) runs the LUT
// on that one; explicit choices are kept.
Backend standaloneDfgBackend(Backend requested, bool deviceNamed);

// Returns the N x N LUT: R = DFG1, G = DFG2, B = renormalized Disney diffuse, A = 1.
// Row y (first scanline first) holds perceptual roughness (y + 0.5) / N, column x holds NoV = (x + 0.5) / N.
ImageRGBA bakeDfgLut(const DfgSettings& settings, const Executor& executor);

} // namespace ibl
