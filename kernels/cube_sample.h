// Filtered cube-map lookups shared by the bake kernels, the CPU backend and the runtime module.
// A pyramid is one flat float array: per level, six faces of (n + 2)^2 RGB texels, each face with a
// one-texel border copied from its neighbours (cube_pyramid.cpp), so that bilinear filtering is
// continuous across face edges and corners without branches. Texels are 3 scalar floats, not
// float3/float4 (see portable.h): a bilinear read's two taps of one row are 6 consecutive floats, which
// integrateLd (ld_lanes.h) reads as one vector.
#ifndef IBL_CUBE_SAMPLE_H
#define IBL_CUBE_SAMPLE_H

#include "cube.h"

IBL_BEGIN_NAMESPACE

#define IBL_MAX_CUBE_LEVELS 16

// A pyramid's shape: a power-of-two base face size and levels down to 1x1, so level m has faces of
// n_m = base >> m and every offset has a closed form (no per-level arrays, which PoCL cannot keep in
// registers across work-items).
IBL_STRUCT(CubePyramidLayout) {
    uint32_t baseFaceSize;
    uint32_t levelCount;
};

IBL_FN uint cubeLevelFaceSize(CubePyramidLayout shape, uint level) {
    return shape.baseFaceSize >> level;
}

// First texel of level m: 6 sum_{k<m} (n_k + 2)^2 with n_k = N / 2^k, i.e.
// 6 [ (4/3)(N^2 - n_m^2) + 8 (N - n_m) + 4 m ] (a geometric series; N^2 - n_m^2 is divisible by 3).
IBL_FN uint cubeLevelTexelOffset(CubePyramidLayout shape, uint level) {
    uint big = shape.baseFaceSize, n = big >> level;
    return 6u * ((4u * (big * big - n * n)) / 3u + 8u * (big - n) + 4u * level);
}

// First float of level m (three per texel).
IBL_FN uint cubeLevelOffset(CubePyramidLayout shape, uint level) {
    return 3u * cubeLevelTexelOffset(shape, level);
}

IBL_FN uint cubePyramidTexelCount(CubePyramidLayout shape) {
    return cubeLevelTexelOffset(shape, shape.levelCount);
}

IBL_FN uint cubePyramidFloatCount(CubePyramidLayout shape) {
    return cubeLevelOffset(shape, shape.levelCount);
}

// The floats a pyramid's storage holds: its texels, then IBL_PYRAMID_TAIL_FLOATS zeros, since integrateLd
// (ld_lanes.h) reads a pair of taps as 8 floats, 2 past the pair's 6, and the last pair ends at the last
// texel.
#define IBL_PYRAMID_TAIL_FLOATS 2u

IBL_FN uint cubePyramidStorageFloatCount(CubePyramidLayout shape) {
    return cubePyramidFloatCount(shape) + IBL_PYRAMID_TAIL_FLOATS;
}

// The texel (x, y) of a face (-1..n, border included) as a texel number: its RGB floats start at 3 times
// it, and a scalar pyramid of the same shape (one float per texel: a local probe's visibility) holds its
// value at it.
IBL_FN uint cubeBorderedTexel(CubePyramidLayout shape, uint level, int face, int x, int y) {
    uint stride = cubeLevelFaceSize(shape, level) + 2u;
    return cubeLevelTexelOffset(shape, level) + (IBL_UINT(face) * stride + IBL_UINT(y + 1)) * stride +
           IBL_UINT(x + 1);
}

IBL_FN uint cubeBorderedTexelIndex(CubePyramidLayout shape, uint level, int face, int x, int y) {
    return 3u * cubeBorderedTexel(shape, level, face, x, y);
}

// A bilinear read of one level at (face, s, t): the texel number of the first of its 2x2 texels, the row
// stride in texels, and the four weights. Texel centres sit at (i + 0.5) / n; the border makes the taps at
// -1 and n valid. The RGB and the scalar reads share it, so both filter with the same weights.
IBL_STRUCT(CubeBilinearTaps) {
    uint32_t texel00; // (x0, y0); (x0 + 1, y0) is texel00 + 1, (x0, y0 + 1) is texel00 + stride
    uint32_t stride;
    float w00, w10, w01, w11;
};

IBL_FN CubeBilinearTaps cubeBilinearTaps(CubePyramidLayout shape, uint level, CubeCoord c) {
    uint size = cubeLevelFaceSize(shape, level);
    float n = IBL_FLOAT(size);
    float x = c.s * n - 0.5f, y = c.t * n - 0.5f;
    float x0f = clamp(floor(x), -1.0f, n - 1.0f), y0f = clamp(floor(y), -1.0f, n - 1.0f);
    float fx = clamp(x - x0f, 0.0f, 1.0f), fy = clamp(y - y0f, 0.0f, 1.0f);
    CubeBilinearTaps taps;
    taps.texel00 = cubeBorderedTexel(shape, level, c.face, IBL_INT(x0f), IBL_INT(y0f));
    taps.stride = size + 2u;
    taps.w00 = (1.0f - fx) * (1.0f - fy);
    taps.w10 = fx * (1.0f - fy);
    taps.w01 = (1.0f - fx) * fy;
    taps.w11 = fx * fy;
    return taps;
}

// Bilinear lookup of one level at (face, s, t).
IBL_FN vec3 cubeSampleLevel(IBL_FLOAT_BUFFER pyramid, CubePyramidLayout shape, uint level, CubeCoord c) {
    CubeBilinearTaps taps = cubeBilinearTaps(shape, level, c);
    uint i00 = 3u * taps.texel00;
    uint i10 = i00 + 3u, i01 = i00 + 3u * taps.stride, i11 = i01 + 3u;
    return weightedRgb4(pyramid, i00, i10, i01, i11, taps.w00, taps.w10, taps.w01, taps.w11);
}

// Pre-filtered importance sampling (Frostbite Listing 19, Krivanek & Colbert 2008): the source level
// whose texels cover the solid angle omegaS = 1 / (n pdf) of one of n samples, omegaP being a level-0
// texel's. Rounded to a whole level: one bilinear read per sample instead of trilinear's two; sample
// tables are shared by all texels, so the rounding makes no texel-to-texel steps.
IBL_FN float prefilteredSourceLevel(uint sampleCount, float pdf, float omegaP, float lodBias, float maxLod) {
    float omegaS = 1.0f / (IBL_FLOAT(sampleCount) * pdf);
    return floor(clamp(0.5f * log2(omegaS / omegaP) + lodBias, 0.0f, maxLod) + 0.5f);
}

// The two levels a trilinear read at fractional level `lod` (clamped to the pyramid) blends, and the
// weight of the second.
IBL_STRUCT(CubeTrilinearLevels) {
    uint32_t level0;
    uint32_t level1;
    float fraction;
};

IBL_FN CubeTrilinearLevels cubeTrilinearLevels(CubePyramidLayout shape, float lod) {
    float maxLevel = IBL_FLOAT(shape.levelCount - 1u);
    float clamped = clamp(lod, 0.0f, maxLevel);
    float l0f = floor(clamped);
    CubeTrilinearLevels levels;
    levels.level0 = IBL_UINT(l0f);
    levels.level1 = min(levels.level0 + 1u, shape.levelCount - 1u);
    levels.fraction = clamped - l0f;
    return levels;
}

// Trilinear lookup in direction d at fractional level `lod` (clamped to the pyramid).
IBL_FN vec3 cubeSampleLod(IBL_FLOAT_BUFFER pyramid, CubePyramidLayout shape, vec3 d, float lod) {
    CubeCoord c = cubeCoordFromDirection(d);
    CubeTrilinearLevels levels = cubeTrilinearLevels(shape, lod);
    vec3 a = cubeSampleLevel(pyramid, shape, levels.level0, c);
    vec3 b = cubeSampleLevel(pyramid, shape, levels.level1, c);
    return v3add(v3scale(a, 1.0f - levels.fraction), v3scale(b, levels.fraction));
}

// The same reads of a scalar pyramid (one float per texel, cubeBorderedTexel), with the RGB reads' weights.
IBL_FN float cubeSampleLevelScalar(IBL_FLOAT_BUFFER pyramid, CubePyramidLayout shape, uint level,
                                   CubeCoord c) {
    CubeBilinearTaps taps = cubeBilinearTaps(shape, level, c);
    uint i00 = taps.texel00, i10 = i00 + 1u, i01 = i00 + taps.stride, i11 = i01 + 1u;
    return taps.w00 * IBL_READ(pyramid, i00) + taps.w10 * IBL_READ(pyramid, i10) +
           taps.w01 * IBL_READ(pyramid, i01) + taps.w11 * IBL_READ(pyramid, i11);
}

IBL_FN float cubeSampleLodScalar(IBL_FLOAT_BUFFER pyramid, CubePyramidLayout shape, vec3 d, float lod) {
    CubeCoord c = cubeCoordFromDirection(d);
    CubeTrilinearLevels levels = cubeTrilinearLevels(shape, lod);
    return cubeSampleLevelScalar(pyramid, shape, levels.level0, c) * (1.0f - levels.fraction) +
           cubeSampleLevelScalar(pyramid, shape, levels.level1, c) * levels.fraction;
}

IBL_END_NAMESPACE

#endif
