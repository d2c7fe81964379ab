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
typedef struct {
    uint32_t baseFaceSize;
    uint32_t levelCount;
} CubePyramidLayout;

IBL_FN uint cubeLevelFaceSize(CubePyramidLayout layout, uint level) {
    return layout.baseFaceSize >> level;
}

// First float of level m: 18 sum_{k<m} (n_k + 2)^2 with n_k = N / 2^k, i.e.
// 18 [ (4/3)(N^2 - n_m^2) + 8 (N - n_m) + 4 m ] (a geometric series; N^2 - n_m^2 is divisible by 3).
IBL_FN uint cubeLevelOffset(CubePyramidLayout layout, uint level) {
    uint big = layout.baseFaceSize, n = big >> level;
    return 18u * ((4u * (big * big - n * n)) / 3u + 8u * (big - n) + 4u * level);
}

IBL_FN uint cubePyramidFloatCount(CubePyramidLayout layout) {
    return cubeLevelOffset(layout, layout.levelCount);
}

IBL_FN uint cubeBorderedTexelIndex(CubePyramidLayout layout, uint level, int face, int x, int y) {
    uint stride = cubeLevelFaceSize(layout, level) + 2u;
    return cubeLevelOffset(layout, level) +
           3u * (((uint)face * stride + (uint)(y + 1)) * stride + (uint)(x + 1));
}

// Bilinear lookup of one level at (face, s, t). Texel centres sit at (i + 0.5) / n; the border makes
// the taps at -1 and n valid.
IBL_FN vec3 cubeSampleLevel(IBL_GLOBAL const float* pyramid, CubePyramidLayout layout, uint level,
                            CubeCoord c) {
    uint size = cubeLevelFaceSize(layout, level);
    float n = (float)size;
    float x = c.s * n - 0.5f, y = c.t * n - 0.5f;
    float x0f = clamp(floor(x), -1.0f, n - 1.0f), y0f = clamp(floor(y), -1.0f, n - 1.0f);
    float fx = clamp(x - x0f, 0.0f, 1.0f), fy = clamp(y - y0f, 0.0f, 1.0f);
    int x0 = (int)x0f, y0 = (int)y0f;
    uint stride = size + 2u;
    uint i00 = cubeBorderedTexelIndex(layout, level, c.face, x0, y0);
    uint i10 = i00 + 3u, i01 = i00 + 3u * stride, i11 = i01 + 3u;
    float w00 = (1.0f - fx) * (1.0f - fy), w10 = fx * (1.0f - fy), w01 = (1.0f - fx) * fy, w11 = fx * fy;
    return v3(
        w00 * pyramid[i00] + w10 * pyramid[i10] + w01 * pyramid[i01] + w11 * pyramid[i11],
        w00 * pyramid[i00 + 1] + w10 * pyramid[i10 + 1] + w01 * pyramid[i01 + 1] + w11 * pyramid[i11 + 1],
        w00 * pyramid[i00 + 2] + w10 * pyramid[i10 + 2] + w01 * pyramid[i01 + 2] + w11 * pyramid[i11 + 2]);
}

// Pre-filtered importance sampling (Frostbite Listing 19, Krivanek & Colbert 2008): the source level
// whose texels cover the solid angle omegaS = 1 / (n pdf) of one of n samples, omegaP being a level-0
// texel's. Rounded to a whole level: one bilinear read per sample instead of trilinear's two; sample
// tables are shared by all texels, so the rounding makes no texel-to-texel steps.
IBL_FN float prefilteredSourceLevel(uint sampleCount, float pdf, float omegaP, float lodBias, float maxLod) {
    float omegaS = 1.0f / ((float)sampleCount * pdf);
    return floor(clamp(0.5f * log2(omegaS / omegaP) + lodBias, 0.0f, maxLod) + 0.5f);
}

// Trilinear lookup in direction d at fractional level `lod` (clamped to the pyramid).
IBL_FN vec3 cubeSampleLod(IBL_GLOBAL const float* pyramid, CubePyramidLayout layout, vec3 d, float lod) {
    CubeCoord c = cubeCoordFromDirection(d);
    float maxLevel = (float)(layout.levelCount - 1u);
    lod = clamp(lod, 0.0f, maxLevel);
    float l0f = floor(lod);
    uint l0 = (uint)l0f;
    uint l1 = min(l0 + 1u, layout.levelCount - 1u);
    float f = lod - l0f;
    vec3 a = cubeSampleLevel(pyramid, layout, l0, c);
    vec3 b = cubeSampleLevel(pyramid, layout, l1, c);
    return v3add(v3scale(a, 1.0f - f), v3scale(b, f));
}

IBL_END_NAMESPACE

#endif
