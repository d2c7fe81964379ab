// Error of a baked cube against a reference cube of the same face size: the metrics the stage tests
// assert and `iblbake accuracy` reports.
#pragma once

#include "iblbake/core/cubemap.h"

namespace ibl {

// sum |a - ref| / sum |ref| over every texel and colour channel (RGB).
double relativeMeanAbsError(const CubeMap& a, const CubeMap& ref);

struct CubeErrors {
    double relativeMeanAbs = 0.0; // relativeMeanAbsError
    // max |a - ref| over texels and channels, over the mean |ref| of that channel: the worst texel in units
    // of the level's mean (a per-texel ratio would blow up on black texels).
    double maxRelativeToMean = 0.0;
    // |sum (a - ref) omega| / sum ref omega, solid-angle weighted, summed over RGB: energy gained or lost.
    double energy = 0.0;
};
CubeErrors compareCubes(const CubeMap& a, const CubeMap& ref);

} // namespace ibl
