// The bright-texel list as the host writes it (baker/src/stages/bright_split.cpp) and the specular (ld.h) and
// irradiance (irradiance.h) kernels read it: the texels split off the source and integrated exactly, their
// components in lanes, and their clusters.
#ifndef IBL_BRIGHT_LIST_H
#define IBL_BRIGHT_LIST_H

#include "lanes.h"

IBL_BEGIN_NAMESPACE

// A list entry has 10 floats: centre direction (3), solid angle, excess radiance (3), face, x, y.
#define IBL_BRIGHT_ENTRY_FLOATS 10

// The entries' first IBL_BRIGHT_LANE_FLOATS floats (centre direction, solid angle, excess RGB) are also in a
// second array component by component: component c of entry i at c * brightLaneStride(count) + i, so that
// brightClusterLd reads a component of 8 consecutive entries as one vector (bright_lanes.h). The stride
// leaves room for a read of 8 from the last entry.
#define IBL_BRIGHT_LANE_FLOATS 7u

IBL_FN uint brightLaneStride(uint entryCount) {
    return (entryCount + 2u * IBL_LANES - 1u) / IBL_LANES * IBL_LANES;
}

// Bright texels are grouped into clusters (IBL_BRIGHT_CLUSTER_FLOATS each: centroid direction (3),
// angular radius, bound on sum of excess * solid angle (max over channels), first entry, entry count,
// cosine of half the angular radius).
#define IBL_BRIGHT_CLUSTER_FLOATS 8

IBL_END_NAMESPACE

#endif
