// Splits a source cube into a residual with its bright texels scaled down (to the mean luminance, or to the
// threshold when there are more than maxTexels) and the sparse excess of those texels (the list kernels/ld.h
// integrates exactly).
#pragma once

#include "iblbake/core/cubemap.h"

#include <cstdint>
#include <functional>
#include <vector>

namespace ibl {

struct BrightTexels {
    std::vector<float> entries;  // IBL_BRIGHT_ENTRY_FLOATS per texel, grouped by cluster
    std::vector<float> clusters; // IBL_BRIGHT_CLUSTER_FLOATS per cluster (kernels/bright_list.h)
    std::uint32_t count() const;
    std::uint32_t clusterCount() const;
};

// The entries' first IBL_BRIGHT_LANE_FLOATS floats component by component (kernels/bright_list.h,
// brightLaneStride), the rest of each component's row zeros.
std::vector<float> brightEntryLanes(const BrightTexels& bright);

struct BrightSplit {
    CubeMap residual;
    BrightTexels bright;
    float thresholdLuminance = 0.0f;
};

// Which texels a split takes out and the factor that scales each down to the luminance it keeps (the mean,
// or the threshold when more than maxTexels exceed it).
struct BrightChoice {
    struct Texel {
        int face, x, y;
        float scale; // kept luminance / the texel's luminance
    };
    std::vector<Texel> texels;
    float thresholdLuminance = 0.0f;
};

// threshold: multiple of the solid-angle-weighted mean luminance; at most maxTexels texels are split
// off (the brightest; the threshold rises when more exceed it).
BrightChoice chooseBrightTexels(const CubeMap& source, float threshold, std::uint32_t maxTexels);

// Splits `cube` at the chosen texels: residual RGB = RGB x scale there (A kept), the excess listed. residual
// + excess == cube exactly. A cube other than the one chosen from is split at the same texels by the same
// factors (a capture's visibility, so that it is filtered with its colour's weights).
BrightSplit applyBrightSplit(const CubeMap& cube, const BrightChoice& choice);

// applyBrightSplit's residual made in `cube` itself for the time of useResidual(cube), then undone (the cube
// holds its own texels again, bit for bit, also when useResidual throws): no copy of the cube. Returns the
// excess, as applyBrightSplit lists it.
BrightTexels withResidualInPlace(CubeMap& cube, const BrightChoice& choice,
                                 const std::function<void(const CubeMap& residual)>& useResidual);

// applyBrightSplit(source, chooseBrightTexels(source, threshold, maxTexels)).
BrightSplit splitBrightTexels(const CubeMap& source, float threshold, std::uint32_t maxTexels);

} // namespace ibl
