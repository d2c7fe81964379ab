// Diffuse (Lambert) pre-integration by cosine importance sampling with pre-filtered lookups (Frostbite
// 2014, eq. 59-62 and Listing 20, with the per-sample source LOD of Listing 19 for pdf = cos / pi).
//
// What is computed, for a texel of direction n: the cosine-weighted mean radiance over the hemisphere,
//   (1 / pi) integral L(l) max(0, n.l) dl = E(n) / pi,
// which is what Listing 20 returns (the sum of L over cosine-distributed samples divided by their
// count), the LD term of a Lambert lobe. Frostbite's runtime multiplies it by the DFG LUT's diffuse
// term and the albedo; a constant environment L gives L (and E = pi L). Irradiance is pi times it.
#ifndef IBL_IRRADIANCE_H
#define IBL_IRRADIANCE_H

#include "bright_list.h" // the bright-texel list is shared with the specular stage
#include "cube_sample.h"
#include "sampling.h"
#include "work_item.h"

IBL_BEGIN_NAMESPACE

// Kernel arguments (fixed-width scalars; layout checked on the host).
typedef struct {
    CubePyramidLayout source;
    uint32_t faceSize;    // output face size
    uint32_t sampleCount; // table entries
    float invSampleCount; // 1 / sampleCount
    uint32_t brightCount; // entries of the bright-texel list
} IrradianceParams;

// One cosine-distributed sample in the texel's tangent frame and the source LOD whose texel solid
// angle matches the sample's (Listing 19 with pdf = cos / pi). 4 floats in the table.
#define IBL_IRRADIANCE_SAMPLE_FLOATS 4
typedef struct {
    float x, y, z;
    float lod;
} IrradianceSample;

// Table entry i of n: a Hammersley point mapped to the hemisphere by Malley's method (area-uniform disk
// point lifted to the hemisphere; pdf = cos / pi). omegaP is the solid angle of one level-0 source
// texel (4 pi / (6 w^2)); lodBias is added to 0.5 log2(omegaS / omegaP), omegaS = 1 / (n pdf).
// The first Hammersley coordinate is (i + 0.5) / n < 1, so every sample is strictly above the horizon.
IBL_FN IrradianceSample irradianceSampleEntry(uint i, uint n, float omegaP, float lodBias, float maxLod) {
    float2 disk = unitDiskPoint(hammersley(i, n));
    vec3 l = cosineSampleFromDisk(disk.x, disk.y);
    float pdf = l.z * IBL_INV_PI;
    IrradianceSample s;
    s.x = l.x;
    s.y = l.y;
    s.z = l.z;
    s.lod = prefilteredSourceLevel(n, pdf, omegaP, lodBias, maxLod);
    return s;
}

// Listing 20 for direction n: (1 / N) sum_i L(l_i) over the table's N cosine-distributed samples,
// each a bilinear lookup at its (whole) level. Returns E(n) / pi.
IBL_FN vec3 integrateIrradiance(vec3 n, IBL_GLOBAL const float* pyramid, CubePyramidLayout layout,
                                IBL_GLOBAL const float* table, uint sampleCount, float invSampleCount) {
    Frame f = frameFromNormal(n);
    float r = 0.0f, g = 0.0f, b = 0.0f;
    for (uint i = 0; i < sampleCount; ++i) {
        IBL_UNIFORM_LOOP_HEAD();
        const IBL_GLOBAL float* e = table + IBL_IRRADIANCE_SAMPLE_FLOATS * i;
        vec3 l = frameToWorld(f, v3(e[0], e[1], e[2]));
        vec3 c = cubeSampleLevel(pyramid, layout, (uint)e[3], cubeCoordFromDirection(l));
        r += c.x;
        g += c.y;
        b += c.z;
    }
    return v3(r * invSampleCount, g * invSampleCount, b * invSampleCount);
}

// The bright texels split off the source (bright_list.h layout: centre direction, solid angle,
// excess radiance, face, x, y) integrated exactly: (1 / pi) sum_b B_b max(0, n.d_b) omega_b, the
// cosine taken at the texel centre (as the brute-force reference does). Returns their E(n) / pi.
IBL_FN vec3 brightTexelsIrradiance(vec3 n, IBL_GLOBAL const float* bright, uint count) {
    float r = 0.0f, g = 0.0f, b = 0.0f;
    for (uint i = 0; i < count; ++i) {
        IBL_UNIFORM_LOOP_HEAD();
        const IBL_GLOBAL float* e = bright + IBL_BRIGHT_ENTRY_FLOATS * i;
        float w = fmax(0.0f, n.x * e[0] + n.y * e[1] + n.z * e[2]) * e[3];
        r += w * e[4];
        g += w * e[5];
        b += w * e[6];
    }
    return v3(r * IBL_INV_PI, g * IBL_INV_PI, b * IBL_INV_PI);
}

// The work-items of irradiance.cl, one output texel (iblbake/opencl/dispatch.h). Two kernels, as for LD
// (ld.h): irradianceSampledItem stores the filtered-importance-sampled part in a loop simple and uniform
// enough for PoCL to vectorize across work-items, irradianceBrightItem adds the bright texels integrated
// exactly.
IBL_FN void irradianceSampledItem(WorkItem t, IBL_GLOBAL float* out, IrradianceParams params,
                                  IBL_GLOBAL const float* pyramid, IBL_GLOBAL const float* table) {
    storeTexel(out, t,
               integrateIrradiance(cubeWorkItemDirection(t, params.faceSize), pyramid, params.source, table,
                                   params.sampleCount, params.invSampleCount));
}

IBL_FN void irradianceBrightItem(WorkItem t, IBL_GLOBAL float* out, IrradianceParams params,
                                 IBL_GLOBAL const float* bright) {
    addToTexel(out, t,
               brightTexelsIrradiance(cubeWorkItemDirection(t, params.faceSize), bright, params.brightCount));
}

IBL_END_NAMESPACE

#endif
