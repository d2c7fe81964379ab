// The sampled part of an LD texel (ld.h): integrateLd with a table block's IBL_LD_BLOCK samples in the lanes
// of float8 vectors (lanes.h), on both backends. The scalar loop ran unvectorized on PoCL at ~80 cycles a
// sample; with the samples in lanes the frame is per work-item and the direction-to-taps steps are vector
// operations, on any device (the arithmetic of frameToWorld, cubeCoordFromDirection and cubeBilinearTaps,
// lane by lane). The texels are not gathered: a bilinear read's left and right taps are 6 consecutive floats,
// so each lane reads its top and its bottom pair as one vector of 8 and weighs it whole. Twelve gathers of 8
// per block were most of the sampled pass on both backends (PoCL's vgatherqps; GCC's scalar loads and
// inserts).
#ifndef IBL_LD_LANES_H
#define IBL_LD_LANES_H

#include "cube_sample.h"
#include "lanes.h"
#include "ld_table.h"
#include "sampling.h"

#if IBL_LD_BLOCK != IBL_LANES
#error "a table block is read as one float8 per component"
#endif

IBL_BEGIN_NAMESPACE

// cubeBilinearTaps(layout, level, cubeCoordFromDirection((dx, dy, dz))) in each lane: the first float of the
// top pair of taps, (x0, y0) and (x0 + 1, y0), whose 6 floats are consecutive; of the bottom pair, one row
// below; and the fractions fx, fy the weights are made of.
IBL_FN void cubeTapPairsLanes(CubePyramidLayout layout, uint8 level, float8 dx, float8 dy, float8 dz,
                              uint8* top, uint8* bottom, float8* fx, float8* fy) {
    // cubeCoordFromDirection: comparisons give -1 (true) or 0 per lane; select(a, b, c) is c ? b : a.
    float8 ax = fabs(dx), ay = fabs(dy), az = fabs(dz);
    int8 xMajor = isgreaterequal(ax, ay) & isgreaterequal(ax, az);
    int8 yMajor = ~xMajor & isgreaterequal(ay, az);
    int8 zMajor = ~xMajor & ~yMajor;
    int8 xPositive = isgreaterequal(dx, 0.0f), yPositive = isgreaterequal(dy, 0.0f),
         zPositive = isgreaterequal(dz, 0.0f);
    int8 face =
        select(select(select((int8)5, (int8)4, zPositive), select((int8)3, (int8)2, yPositive), yMajor),
               select((int8)1, (int8)0, xPositive), xMajor);
    float8 major = select(select(az, ay, yMajor), ax, xMajor);
    float8 sc = select(select(dx, -dx, zMajor & isless(dz, 0.0f)), select(dz, -dz, xPositive), xMajor);
    float8 tc = select(-dy, select(-dz, dz, yPositive), yMajor);
    float8 inv = 0.5f / major;
    float8 s = sc * inv + 0.5f, t = tc * inv + 0.5f;
    // cubeBilinearTaps with cubeBorderedTexel and cubeLevelTexelOffset.
    uint8 big = (uint8)layout.baseFaceSize, size = big >> level;
    float8 n = convert_float8(size);
    float8 x = s * n - 0.5f, y = t * n - 0.5f;
    float8 x0f = clamp(floor(x), -1.0f, n - 1.0f), y0f = clamp(floor(y), -1.0f, n - 1.0f);
    *fx = clamp(x - x0f, 0.0f, 1.0f);
    *fy = clamp(y - y0f, 0.0f, 1.0f);
    uint8 stride = size + 2u;
    uint8 levelOffset = 6u * ((4u * (big * big - size * size)) / 3u + 8u * (big - size) + 4u * level);
    uint8 texel00 = levelOffset + (as_uint8(face) * stride + as_uint8(convert_int8(y0f) + 1)) * stride +
                    as_uint8(convert_int8(x0f) + 1);
    *top = 3u * texel00;
    *bottom = *top + 3u * stride;
}

// Lane k's weights of a pair of taps, (left, left, left, right, right, right, left, left): the last two
// multiply the 2 floats after the pair, which integrateLd never reads back.
IBL_FN float8 tapPairWeights(float8 left, float8 right, uint k) {
#ifdef __OPENCL_VERSION__
    return shuffle2(left, right, (uint8)(k, k, k, k + 8u, k + 8u, k + 8u, k, k));
#elif defined(__clang__)
    // Clang's __builtin_shufflevector takes constant indices only; its builds (the sanitizer's) need no
    // speed.
    float l = left.v[k], r = right.v[k];
    return float8(FloatLanes{l, l, l, r, r, r, l, l});
#else
    int i = int(k), j = int(k) + 8;
    return float8(__builtin_shuffle(left.v, right.v, IntLanes{i, i, i, j, j, j, i, i}));
#endif
}

// Lane k's sample: its two pairs of taps, each one read of 8 floats, times their weights.
IBL_FN float8 tapPairsLane(IBL_GLOBAL const float* pyramid, uint top, uint bottom, float8 w00, float8 w10,
                           float8 w01, float8 w11, uint k) {
    return vload8(0, pyramid + top) * tapPairWeights(w00, w10, k) +
           vload8(0, pyramid + bottom) * tapPairWeights(w01, w11, k);
}

// LD for the output direction n: sum of L(l) NoL / sum of NoL over the level's table of sampleCount
// samples (a whole number of blocks), with `invWeightSum` = 1 / sum of the weights; a table block's samples
// in the lanes of float8 vectors.
// A table block at a time; lane k's samples sum into sk, whose RGB are its first 3 floats plus its next 3.
IBL_FN vec3 integrateLd(vec3 normal, IBL_GLOBAL const float* pyramid, CubePyramidLayout layout,
                        IBL_GLOBAL const float* table, uint sampleCount, float invWeightSum) {
    Frame f = frameFromNormal(normal);
    float8 s0 = 0.0f, s1 = 0.0f, s2 = 0.0f, s3 = 0.0f, s4 = 0.0f, s5 = 0.0f, s6 = 0.0f, s7 = 0.0f;
    for (uint first = 0; first < sampleCount; first += IBL_LD_BLOCK) {
        IBL_GLOBAL const float* block = table + ldTableIndex(first, 0u);
        float8 sx = vload8(0, block), sy = vload8(1, block), sz = vload8(2, block);
        float8 weight = vload8(3, block);
        uint8 level = convert_uint8(vload8(4, block));
        // frameToWorld: t x + (b y + n z), per component.
        float8 lx = f.t.x * sx + (f.b.x * sy + f.n.x * sz);
        float8 ly = f.t.y * sx + (f.b.y * sy + f.n.y * sz);
        float8 lz = f.t.z * sx + (f.b.z * sy + f.n.z * sz);
        uint8 topLanes, bottomLanes;
        float8 fx, fy;
        cubeTapPairsLanes(layout, level, lx, ly, lz, &topLanes, &bottomLanes, &fx, &fy);
        // The bilinear weights (cubeBilinearTaps') times the sample's.
        float8 upper = (1.0f - fy) * weight, lower = fy * weight;
        float8 w00 = (1.0f - fx) * upper, w10 = fx * upper, w01 = (1.0f - fx) * lower, w11 = fx * lower;
        uint top[IBL_LANES], bottom[IBL_LANES];
        vstore8(topLanes, 0, top);
        vstore8(bottomLanes, 0, bottom);
        s0 += tapPairsLane(pyramid, top[0], bottom[0], w00, w10, w01, w11, 0u);
        s1 += tapPairsLane(pyramid, top[1], bottom[1], w00, w10, w01, w11, 1u);
        s2 += tapPairsLane(pyramid, top[2], bottom[2], w00, w10, w01, w11, 2u);
        s3 += tapPairsLane(pyramid, top[3], bottom[3], w00, w10, w01, w11, 3u);
        s4 += tapPairsLane(pyramid, top[4], bottom[4], w00, w10, w01, w11, 4u);
        s5 += tapPairsLane(pyramid, top[5], bottom[5], w00, w10, w01, w11, 5u);
        s6 += tapPairsLane(pyramid, top[6], bottom[6], w00, w10, w01, w11, 6u);
        s7 += tapPairsLane(pyramid, top[7], bottom[7], w00, w10, w01, w11, 7u);
    }
    // Pairwise, as sumLanes.
    float8 sum = ((s0 + s4) + (s1 + s5)) + ((s2 + s6) + (s3 + s7));
#ifdef __OPENCL_VERSION__
    float red = sum.s0 + sum.s3, green = sum.s1 + sum.s4, blue = sum.s2 + sum.s5;
#else
    float red = sum.v[0] + sum.v[3], green = sum.v[1] + sum.v[4], blue = sum.v[2] + sum.v[5];
#endif
    return v3(red * invWeightSum, green * invWeightSum, blue * invWeightSum);
}

IBL_END_NAMESPACE

#endif
