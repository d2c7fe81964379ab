// Splits a source cube into a residual with its bright texels scaled down (to the mean luminance, or to the
// threshold when there are more than maxTexels) and the sparse excess of those texels (the list kernels/ld.h
// integrates exactly).
#pragma once

#include "iblbake/core/cubemap.h"

#include <cstdint>
#include <vector>

namespace ibl {

struct BrightTexels {
    std::vector<float> entries;  // IBL_BRIGHT_ENTRY_FLOATS per texel, grouped by cluster
    std::vector<float> clusters; // IBL_BRIGHT_CLUSTER_FLOATS per cluster (kernels/ld.h)
    std::uint32_t count() const;
    std::uint32_t clusterCount() const;
};

struct BrightSplit {
    CubeMap residual;
    BrightTexels bright;
    float thresholdLuminance = 0.0f;
};

// threshold: multiple of the solid-angle-weighted mean luminance; at most maxTexels texels are split
// off (the brightest; the threshold rises when more exceed it). residual + excess == source exactly.
BrightSplit splitBrightTexels(const CubeMap& source, float threshold, std::uint32_t maxTexels);

} // namespace ibl
