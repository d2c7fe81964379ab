// For brightTexelsLd (ld.h): brightClusterLd with IBL_LANES bright entries of a cluster in the lanes of
// float8 vectors (lanes.h). With a sun's long GGX tail, most output texels of levels 1-3 take every entry of
// the sun's clusters, nearly all of them at their point value (brightTexelWeight's last case); one entry at a
// time, that loop was most of the bright pass. A block of entries runs in lanes when each of its entries
// takes the point value, and one entry at a time (brightEntryWeight) when any needs a sub-grid, the closed
// form or the footprint. A block's centre directions, solid angles and excesses are vector reads of the
// entries in lanes (brightLaneStride), not gathers of the list's entries: 7 gathers were most of a block's
// time on PoCL.
#ifndef IBL_BRIGHT_LANES_H
#define IBL_BRIGHT_LANES_H

#include "bright_entry_weight.h"
#include "bright_list.h"
#include "footprint_lanes.h"
#include "lanes.h"

IBL_BEGIN_NAMESPACE

// The sum of the entries [first, first + count) of a cluster weighted by brightEntryWeight, with the entries
// in vector lanes where each takes its point value.
IBL_FN vec3 brightClusterLd(BrightTarget* t, IBL_GLOBAL const float* bright, IBL_GLOBAL const float* lanes,
                            uint laneStride, uint first, uint count, float alpha, float texelSize) {
    float8 r = 0.0f, g = 0.0f, b = 0.0f;
    vec3 oneByOne = v3(0.0f, 0.0f, 0.0f);
    int end = (int)(first + count);
    bool closedFormPossible = 4.0f * alpha < texelSize; // narrowLobeClosedFormApplies' first half
    float closedFormAngle = fmin(3.0f * texelSize, 0.5f), nearAngle = t->footprint ? 3.0f * t->size : 0.0f;
    for (int block = (int)first; block < end; block += (int)IBL_LANES) {
        int8 valid = block + laneIndices() < end;
        // Component c of the block's entries (lanes past the cluster's end read the next entries or zeros).
        IBL_GLOBAL const float* at = lanes + block;
        float8 dx = vload8(0, at), dy = vload8(0, at + laneStride), dz = vload8(0, at + 2u * laneStride);
        // brightTexelWeight's and brightEntryWeight's choices, lane by lane.
        float8 cosAngle = t->centre.x * dx + t->centre.y * dy + t->centre.z * dz;
        float8 angle, subdivisions;
        int8 point = brightPointValueLanes(cosAngle, alpha, texelSize, &angle, &subdivisions);
        point &=
            ~(closedFormPossible ? isless(angle, closedFormAngle) : (int8)0) &
            isgreaterequal(angle, nearAngle); // not brightEntryNearFootprint (every lane without a footprint)
        if (any(valid & ~point)) {
            int blockEnd = block + (int)IBL_LANES < end ? block + (int)IBL_LANES : end;
            for (int i = block; i < blockEnd; ++i) {
                const IBL_GLOBAL float* e = bright + IBL_BRIGHT_ENTRY_FLOATS * i;
                float weight = brightEntryWeight(t, e, alpha, texelSize);
                oneByOne = v3add(oneByOne, v3(weight * e[4], weight * e[5], weight * e[6]));
            }
            continue;
        }
        float8 weight = select((float8)0.0f,
                               brightPointWeightLanes(t->centre.x, t->centre.y, t->centre.z, dx, dy, dz,
                                                      cosAngle, vload8(0, at + 3u * laneStride), alpha),
                               valid);
        r += weight * vload8(0, at + 4u * laneStride);
        g += weight * vload8(0, at + 5u * laneStride);
        b += weight * vload8(0, at + 6u * laneStride);
    }
    return v3add(oneByOne, v3(sumLanes(r), sumLanes(g), sumLanes(b)));
}

IBL_END_NAMESPACE

#endif
