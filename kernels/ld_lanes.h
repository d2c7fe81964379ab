// Included by ld.h: integrateLd with a table block's IBL_LD_BLOCK samples in the lanes of float8 vectors
// (lanes.h), on both backends. The scalar loop ran unvectorized on PoCL at ~80 cycles a sample; with the
// samples in lanes the frame is per work-item and every per-sample step but the texel reads is a vector
// operation, on any device. Same arithmetic as frameToWorld, cubeCoordFromDirection, cubeBilinearTaps and
// cubeSampleLevel, lane by lane; the lanes' sums are added at the end.
#ifndef IBL_LD_LANES_H
#define IBL_LD_LANES_H

#include "lanes.h"

#if IBL_LD_BLOCK != IBL_LANES
#error "a table block is read as one float8 per component"
#endif

// cubeSampleLevel(pyramid, layout, level, cubeCoordFromDirection((dx, dy, dz))) in each lane, into r, g, b.
IBL_FN void cubeSampleLanes(IBL_GLOBAL const float* pyramid, CubePyramidLayout layout, uint8 level, float8 dx,
                            float8 dy, float8 dz, float8* r, float8* g, float8* b) {
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
    float8 fx = clamp(x - x0f, 0.0f, 1.0f), fy = clamp(y - y0f, 0.0f, 1.0f);
    uint8 stride = size + 2u;
    uint8 levelOffset = 6u * ((4u * (big * big - size * size)) / 3u + 8u * (big - size) + 4u * level);
    uint8 texel00 = levelOffset + (as_uint8(face) * stride + as_uint8(convert_int8(y0f) + 1)) * stride +
                    as_uint8(convert_int8(x0f) + 1);
    float8 w00 = (1.0f - fx) * (1.0f - fy), w10 = fx * (1.0f - fy), w01 = (1.0f - fx) * fy, w11 = fx * fy;
    uint8 i00 = 3u * texel00, i10 = i00 + 3u, i01 = i00 + 3u * stride, i11 = i01 + 3u;
    *r = w00 * readLanes(pyramid, i00) + w10 * readLanes(pyramid, i10) + w01 * readLanes(pyramid, i01) +
         w11 * readLanes(pyramid, i11);
    *g = w00 * readLanes(pyramid, i00 + 1u) + w10 * readLanes(pyramid, i10 + 1u) +
         w01 * readLanes(pyramid, i01 + 1u) + w11 * readLanes(pyramid, i11 + 1u);
    *b = w00 * readLanes(pyramid, i00 + 2u) + w10 * readLanes(pyramid, i10 + 2u) +
         w01 * readLanes(pyramid, i01 + 2u) + w11 * readLanes(pyramid, i11 + 2u);
}

// A table block at a time.
IBL_FN vec3 integrateLd(vec3 normal, IBL_GLOBAL const float* pyramid, CubePyramidLayout layout,
                        IBL_GLOBAL const float* table, uint sampleCount, float invWeightSum) {
    Frame f = frameFromNormal(normal);
    float8 r = 0.0f, g = 0.0f, b = 0.0f;
    for (uint first = 0; first < sampleCount; first += IBL_LD_BLOCK) {
        IBL_GLOBAL const float* block = table + ldTableIndex(first, 0u);
        float8 sx = vload8(0, block), sy = vload8(1, block), sz = vload8(2, block);
        float8 weight = vload8(3, block);
        uint8 level = convert_uint8(vload8(4, block));
        // frameToWorld: t x + (b y + n z), per component.
        float8 lx = f.t.x * sx + (f.b.x * sy + f.n.x * sz);
        float8 ly = f.t.y * sx + (f.b.y * sy + f.n.y * sz);
        float8 lz = f.t.z * sx + (f.b.z * sy + f.n.z * sz);
        float8 cr, cg, cb;
        cubeSampleLanes(pyramid, layout, level, lx, ly, lz, &cr, &cg, &cb);
        r += cr * weight;
        g += cg * weight;
        b += cb * weight;
    }
    return v3(sumLanes(r) * invWeightSum, sumLanes(g) * invWeightSum, sumLanes(b) * invWeightSum);
}

#endif
