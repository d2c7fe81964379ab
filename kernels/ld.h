// Specular LD pre-integration with N = V = R by filtered importance sampling (Frostbite 2014,
// Listing 19 and eq. 53; Krivanek & Colbert 2008): the kernel arguments and work-items of one level, and the
// bright pass over a level's clusters. The headers below it, each including what it uses (lane code above the
// scalar code it calls, no name passed both ways):
//   ld_table.h             the level's sample table
//   ld_lanes.h             the sampled part, a table block in lanes (integrateLd)
//   bright_list.h          the bright-texel list's layout
//   narrow_lobe.h          the closed form for lobes much narrower than a texel
//   bright_texel.h         one bright texel for the lobe around one direction
//   narrow_lobe_lanes.h    a bright texel's patches in lanes, for the closed form
//   footprint_lanes.h      an output texel's patches in lanes
//   bright_entry_weight.h  one bright entry for one output texel, at its centre or over its footprint
//   bright_lanes.h         a cluster's entries in lanes (brightClusterLd)
#ifndef IBL_LD_H
#define IBL_LD_H

#include "brdf.h"
#include "bright_entry_weight.h"
#include "bright_lanes.h"
#include "bright_list.h"
#include "cube.h"
#include "cube_sample.h"
#include "ld_lanes.h"
#include "ld_table.h"
#include "sampling.h"
#include "work_item.h"

IBL_BEGIN_NAMESPACE

// Kernel arguments of one LD level (fixed-width scalars; layout checked on the host).
typedef struct {
    CubePyramidLayout source;
    uint32_t faceSize;         // output face size of this level
    uint32_t sampleCount;      // table entries
    float invWeightSum;        // 1 / sum of the table's weights
    uint32_t brightCount;      // clusters of the bright-texel list
    float alpha;               // GGX alpha of this level
    float invLobeIntegral;     // 1 / W(alpha), W = integral of D(h) NoL dl (N = V)
    uint32_t brightLaneStride; // brightLaneStride(entries of the bright-texel list)
} LdParams;

// Bright texels are taken out of the pre-filtered source and integrated exactly: with a sun 10^5 times
// brighter than the sky, the few samples of filtered importance sampling that land near it decide the
// result (noise, ghosts), and the long GGX tail carries visible energy even at low roughness. The source
// is split linearly, L = R + B: R is the source with bright texels scaled down (bright_split.h; filtered
// importance sampling handles it well), B the sparse excess, whose contribution
// sum_b B_b integral_texel D(h) NoL dl / W(alpha) is summed here over every bright texel (bright_list.h).
// A cluster (bright_list.h) whose largest possible contribution, D at its nearest point times its energy,
// stays under `skipBelow` is skipped: the caller sets skipBelow to 1e-3 of the texel's sampled value divided
// by the cluster count, so all skipped clusters together change a texel by under 0.1%. The bright part of
// output texel (face, x, y) of an n-texel level: at its centre, or over its footprint where
// ldFootprintApplies.

// cos(max(angle - radius - reach, 0) / 2) for a direction at cosine cosAngle from a cluster's centroid: the
// half-angle of the nearest point of the cluster widened by reach (1 within it), from the half angles'
// cosines and sines by the angle-difference identity. Square roots only: acos and cos per cluster and
// texel were a large part of the bright pass on PoCL, whose acos/cos are SLEEF's.
IBL_FN float cosHalfNearestAngle(float cosAngle, float cosHalfRadius, float cosHalfReach,
                                 float sinHalfReach) {
    float sinHalfRadius = sqrt(fmax(0.0f, 1.0f - cosHalfRadius * cosHalfRadius));
    float cosHalfBound =
        cosHalfRadius * cosHalfReach - sinHalfRadius * sinHalfReach; // of (radius + reach) / 2
    float sinHalfBound = sinHalfRadius * cosHalfReach + cosHalfRadius * sinHalfReach;
    float cosHalf = sqrt(fmax(0.0f, 0.5f * (1.0f + cosAngle)));
    float sinHalf = sqrt(fmax(0.0f, 0.5f * (1.0f - cosAngle)));
    // Half angles lie in [0, pi / 2], where cos falls: within the widened cluster iff cosHalf >=
    // cosHalfBound.
    return cosHalf >= cosHalfBound ? 1.0f : cosHalf * cosHalfBound + sinHalf * sinHalfBound;
}

IBL_FN vec3 brightTexelsLd(int face, uint x, uint y, uint n, IBL_GLOBAL const float* clusters,
                           uint clusterCount, IBL_GLOBAL const float* bright,
                           IBL_GLOBAL const float* brightLanes, uint laneStride, float alpha,
                           float invLobeIntegral, uint sourceFaceSize, float skipBelow) {
    float texelSize = 2.0f / (float)sourceFaceSize;
    BrightTarget t;
    t.centre = cubeTexelDirection(face, x, y, n);
    t.frame = frameFromNormal(t.centre);
    t.face = face;
    t.size = 2.0f / (float)n;
    t.u0 = -1.0f + (float)x * t.size;
    t.v0 = -1.0f + (float)y * t.size;
    t.footprint = ldFootprintApplies(alpha, n);
    t.solidAngle = -1.0f;
    // A footprint reaches half a diagonal (~0.71 size radians or less) from its centre.
    float reach = t.footprint ? 0.71f * t.size : 0.0f;
    float cosHalfReach = cos(0.5f * reach), sinHalfReach = sin(0.5f * reach);
    vec3 sum = v3(0.0f, 0.0f, 0.0f);
    for (uint c = 0; c < clusterCount; ++c) {
        const IBL_GLOBAL float* cl = clusters + IBL_BRIGHT_CLUSTER_FLOATS * c;
        float cosAngle = t.centre.x * cl[0] + t.centre.y * cl[1] + t.centre.z * cl[2];
        // D at the nearest member (D falls with theta_h, half the angle to it) times the cluster's energy.
        float bound = D_GGX(cosHalfNearestAngle(cosAngle, cl[7], cosHalfReach, sinHalfReach), alpha) * cl[4] *
                      invLobeIntegral;
        if (bound < skipBelow) continue;
        sum = v3add(sum, brightClusterLd(&t, bright, brightLanes, laneStride, (uint)cl[5], (uint)cl[6], alpha,
                                         texelSize));
    }
    return v3scale(sum, invLobeIntegral);
}

// The skip threshold for a texel whose sampled (residual) value is `sampled`.
IBL_FN float brightSkipThreshold(vec3 sampled, uint clusterCount) {
    float value = fmax(sampled.x, fmax(sampled.y, sampled.z));
    return clusterCount > 0u ? 1e-3f * value / (float)clusterCount : 0.0f;
}

// The work-items of ld.cl and of the CPU backend (ld_host_items.cpp), one texel of one level
// (iblbake/opencl/dispatch.h): ldLevelItem stores the sampled part, ldBrightItem then adds the exactly
// integrated bright texels to it. Two kernels, so that the filtered-importance-sampling loop stays uniform
// and simple enough for PoCL to vectorize.
IBL_FN void ldLevelItem(WorkItem t, IBL_GLOBAL float* out, LdParams params, IBL_GLOBAL const float* pyramid,
                        IBL_GLOBAL const float* table) {
    storeTexel(out, t,
               integrateLd(cubeWorkItemDirection(t, params.faceSize), pyramid, params.source, table,
                           params.sampleCount, params.invWeightSum));
}

// A texel's sampled part plus its bright texels, as ldBrightItem adds them to the stored sampled part.
IBL_FN vec3 ldWithBrightTexels(WorkItem t, vec3 sampled, LdParams params, IBL_GLOBAL const float* clusters,
                               IBL_GLOBAL const float* bright, IBL_GLOBAL const float* brightLanes) {
    float skipBelow = brightSkipThreshold(sampled, params.brightCount);
    return v3add(sampled, brightTexelsLd((int)t.face, t.x, t.y, params.faceSize, clusters, params.brightCount,
                                         bright, brightLanes, params.brightLaneStride, params.alpha,
                                         params.invLobeIntegral, params.source.baseFaceSize, skipBelow));
}

IBL_FN void ldBrightItem(WorkItem t, IBL_GLOBAL float* out, LdParams params, IBL_GLOBAL const float* clusters,
                         IBL_GLOBAL const float* bright, IBL_GLOBAL const float* brightLanes) {
    storeTexel(out, t, ldWithBrightTexels(t, loadTexel(out, t), params, clusters, bright, brightLanes));
}

// Levels of at most IBL_LD_ONE_PASS_FACE_SIZE texels a side (at most 96 texels) take both parts in one
// work-item and one dispatch: so few items leave nothing for a vectorizer across them, and PoCL's 4-, 2- and
// 1-px levels went from 1.79, 1.00, 0.49 to 1.58, 0.95, 0.48 ms (bench bakeChainLevels, medians of 7). The
// sampled part stays in registers, so the item still reads no output of its own, and the sum is the same
// float addition as the two passes' (the same bytes).
#define IBL_LD_ONE_PASS_FACE_SIZE 4u

IBL_FN void ldOnePassItem(WorkItem t, IBL_GLOBAL float* out, LdParams params, IBL_GLOBAL const float* pyramid,
                          IBL_GLOBAL const float* table, IBL_GLOBAL const float* clusters,
                          IBL_GLOBAL const float* bright, IBL_GLOBAL const float* brightLanes) {
    storeTexel(out, t,
               ldWithBrightTexels(t,
                                  integrateLd(cubeWorkItemDirection(t, params.faceSize), pyramid,
                                              params.source, table, params.sampleCount, params.invWeightSum),
                                  params, clusters, bright, brightLanes));
}

IBL_END_NAMESPACE

#endif
