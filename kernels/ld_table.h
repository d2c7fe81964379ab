// The sample table of one LD level (ld.h): what filtered importance sampling reads per sample, computed once
// per level by the host (ldSampleEntry, Frostbite 2014 Listing 19) and read a block at a time by integrateLd
// (ld_lanes.h).
#ifndef IBL_LD_TABLE_H
#define IBL_LD_TABLE_H

#include "brdf.h"
#include "cube_sample.h"
#include "sampling.h"

IBL_BEGIN_NAMESPACE

// One sample of a level's table, in the texel's tangent frame: light direction, its weight NoL, and
// the source LOD whose texel solid angle matches the sample's (Listing 19). Everything here depends
// on the level only, so the host computes it once per level. IBL_LD_SAMPLE_FLOATS floats in the table,
// in this order, stored in blocks of IBL_LD_BLOCK samples component by component (the block's x, then its
// y, z, weight and lod: ldTableIndex) and padded to whole blocks with weight-0 samples, which add exact
// zeros: integrateLd reads a block's components as vectors (ld_lanes.h).
#define IBL_LD_SAMPLE_FLOATS 5
#define IBL_LD_BLOCK 8u

// Where component `component` (0..4 as above) of sample i is in a table.
IBL_FN uint ldTableIndex(uint i, uint component) {
    return IBL_LD_SAMPLE_FLOATS * IBL_LD_BLOCK * (i / IBL_LD_BLOCK) + IBL_LD_BLOCK * component +
           i % IBL_LD_BLOCK;
}
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
    s.lod = prefilteredSourceLevel(n, pdf, omegaP, lodBias, maxLod);
    return s;
}

IBL_END_NAMESPACE

#endif
