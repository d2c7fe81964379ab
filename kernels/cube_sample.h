// Filtered cube-map lookups shared by the bake kernels, the CPU backend and the runtime module.
// A pyramid is one flat float array: per level, six faces of (n + 2)^2 RGB texels, each face with a
// one-texel border copied from its neighbours (cube_pyramid.cpp), so that bilinear filtering is
// continuous across face edges and corners without branches. Texels are 3 scalar floats, not
// float3/float4, which keeps gathers vectorizable on CPU devices (see portable.h).
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

// First float of level m: 18 sum_{k<m} (n_k + 2)^2 with n_k = N / 2^k, i.e.
// 18 [ (4/3)(N^2 - n_m^2) + 8 (N - n_m) + 4 m ] (a geometric series; N^2 - n_m^2 is divisible by 3).
IBL_FN uint cubeLevelOffset(CubePyramidLayout shape, uint level) {
    uint big = shape.baseFaceSize, n = big >> level;
    return 18u * ((4u * (big * big - n * n)) / 3u + 8u * (big - n) + 4u * level);
}

IBL_FN uint cubePyramidFloatCount(CubePyramidLayout shape) {
    return cubeLevelOffset(shape, shape.levelCount);
}

IBL_FN uint cubeBorderedTexelIndex(CubePyramidLayout shape, uint level, int face, int x, int y) {
    uint stride = cubeLevelFaceSize(shape, level) + 2u;
    return cubeLevelOffset(shape, level) +
           3u * ((IBL_UINT(face) * stride + IBL_UINT(y + 1)) * stride + IBL_UINT(x + 1));
}

// Bilinear lookup of one level at (face, s, t). Texel centres sit at (i + 0.5) / n; the border makes
// the taps at -1 and n valid.
IBL_FN vec3 cubeSampleLevel(IBL_FLOAT_BUFFER pyramid, CubePyramidLayout shape, uint level, CubeCoord c) {
    uint size = cubeLevelFaceSize(shape, level);
    float n = IBL_FLOAT(size);
    float x = c.s * n - 0.5f, y = c.t * n - 0.5f;
    float x0f = clamp(floor(x), -1.0f, n - 1.0f), y0f = clamp(floor(y), -1.0f, n - 1.0f);
    float fx = clamp(x - x0f, 0.0f, 1.0f), fy = clamp(y - y0f, 0.0f, 1.0f);
    int x0 = IBL_INT(x0f), y0 = IBL_INT(y0f);
    uint stride = size + 2u;
    uint i00 = cubeBorderedTexelIndex(shape, level, c.face, x0, y0);
    uint i10 = i00 + 3u, i01 = i00 + 3u * stride, i11 = i01 + 3u;
    float w00 = (1.0f - fx) * (1.0f - fy), w10 = fx * (1.0f - fy), w01 = (1.0f - fx) * fy, w11 = fx * fy;
    return v3(w00 * IBL_READ(pyramid, i00) + w10 * IBL_READ(pyramid, i10) + w01 * IBL_READ(pyramid, i01) +
                  w11 * IBL_READ(pyramid, i11),
              w00 * IBL_READ(pyramid, i00 + 1u) + w10 * IBL_READ(pyramid, i10 + 1u) +
                  w01 * IBL_READ(pyramid, i01 + 1u) + w11 * IBL_READ(pyramid, i11 + 1u),
              w00 * IBL_READ(pyramid, i00 + 2u) + w10 * IBL_READ(pyramid, i10 + 2u) +
                  w01 * IBL_READ(pyramid, i01 + 2u) + w11 * IBL_READ(pyramid, i11 + 2u));
}

// Pre-filtered importance sampling (Frostbite Listing 19, Krivanek & Colbert 2008): the source level
// whose texels cover the solid angle omegaS = 1 / (n pdf) of one of n samples, omegaP being a level-0
// texel's. Rounded to a whole level: one bilinear read per sample instead of trilinear's two; sample
// tables are shared by all texels, so the rounding makes no texel-to-texel steps.
IBL_FN float prefilteredSourceLevel(uint sampleCount, float pdf, float omegaP, float lodBias, float maxLod) {
    float omegaS = 1.0f / (IBL_FLOAT(sampleCount) * pdf);
    return floor(clamp(0.5f * log2(omegaS / omegaP) + lodBias, 0.0f, maxLod) + 0.5f);
}

// Trilinear lookup in direction d at fractional level `lod` (clamped to the pyramid).
IBL_FN vec3 cubeSampleLod(IBL_FLOAT_BUFFER pyramid, CubePyramidLayout shape, vec3 d, float lod) {
    CubeCoord c = cubeCoordFromDirection(d);
    float maxLevel = IBL_FLOAT(shape.levelCount - 1u);
    lod = clamp(lod, 0.0f, maxLevel);
    float l0f = floor(lod);
    uint l0 = IBL_UINT(l0f);
    uint l1 = min(l0 + 1u, shape.levelCount - 1u);
    float f = lod - l0f;
    vec3 a = cubeSampleLevel(pyramid, shape, l0, c);
    vec3 b = cubeSampleLevel(pyramid, shape, l1, c);
    return v3add(v3scale(a, 1.0f - f), v3scale(b, f));
}

IBL_END_NAMESPACE

#endif
