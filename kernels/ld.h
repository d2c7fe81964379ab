// Specular LD pre-integration with N = V = R by filtered importance sampling (Frostbite 2014,
// Listing 19 and eq. 53; Krivanek & Colbert 2008).
#ifndef IBL_LD_H
#define IBL_LD_H

#include "brdf.h"
#include "cube_sample.h"
#include "sampling.h"

IBL_BEGIN_NAMESPACE

// Kernel arguments of one LD level (fixed-width scalars; layout checked on the host).
typedef struct {
    CubePyramidLayout source;
    uint32_t faceSize;    // output face size of this level
    uint32_t sampleCount; // table entries
    float invWeightSum;   // 1 / sum of the table's weights
} LdParams;

// One sample of a level's table, in the texel's tangent frame: light direction, its weight NoL, and
// the source LOD whose texel solid angle matches the sample's (Listing 19). Everything here depends
// on the level only, so the host computes it once per level.
typedef struct {
    float x, y, z;
    float weight; // NoL
    float lod;
} LdSample;

// Table entry for sample i of n at GGX alpha, or weight 0 when the sample falls below the horizon.
// omegaP is the solid angle of one level-0 source texel (4 pi / (6 w^2)); lodBias is added to
// 0.5 log2(omegaS / omegaP).
IBL_FN LdSample ldSampleEntry(uint i, uint n, float alpha, float omegaP, float lodBias, float maxLod) {
    float2 u = hammersley(i, n);
    float phi = 2.0f * IBL_PI * u.y;
    vec3 h = sampleGGXHalfVector(u.x, cos(phi), sin(phi), alpha);
    vec3 l = reflectAbout(v3(0.0f, 0.0f, 1.0f), h);
    LdSample s;
    s.x = l.x;
    s.y = l.y;
    s.z = l.z;
    s.weight = fmax(l.z, 0.0f);
    // With N = V, NoH = VoH and the pdf D NoH / (4 VoH) reduces to D / 4 (Listing 19's comment).
    float pdf = D_GGX(h.z, alpha) * 0.25f;
    float omegaS = 1.0f / ((float)n * pdf);
    s.lod = clamp(0.5f * log2(omegaS / omegaP) + lodBias, 0.0f, maxLod);
    return s;
}

// LD for the output direction n: sum of L(l) NoL / sum of NoL over the level's table (5 floats per
// sample: x, y, z, weight, lod), with `invWeightSum` = 1 / sum of the weights.
IBL_FN vec3 integrateLd(vec3 n, IBL_GLOBAL const float* pyramid, CubePyramidLayout layout,
                        IBL_GLOBAL const float* table, uint sampleCount, float invWeightSum) {
    Frame f = frameFromNormal(n);
    float r = 0.0f, g = 0.0f, b = 0.0f;
    for (uint i = 0; i < sampleCount; ++i) {
        IBL_UNIFORM_LOOP_HEAD();
        const IBL_GLOBAL float* e = table + 5 * i;
        vec3 l = frameToWorld(f, v3(e[0], e[1], e[2]));
        vec3 c = cubeSampleLod(pyramid, layout, l, e[4]);
        r += c.x * e[3];
        g += c.y * e[3];
        b += c.z * e[3];
    }
    return v3(r * invWeightSum, g * invWeightSum, b * invWeightSum);
}

IBL_END_NAMESPACE

#endif
