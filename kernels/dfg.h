// DFG / diffuse LUT texel integration (Frostbite 2014, Listing 18 and eq. 55-58; layout in
// docs/conventions.md).
#ifndef IBL_DFG_H
#define IBL_DFG_H

#include "brdf.h"
#include "sampling.h"
#include "work_item.h"

IBL_BEGIN_NAMESPACE

// Kernel arguments of the DFG stage: fixed-width scalars only (layout checked on the host).
typedef struct {
    uint32_t size;        // N: the LUT is N x N
    uint32_t firstSample; // this dispatch integrates samples [firstSample, endSample) ...
    uint32_t endSample;   // ... and stores their sums
} DfgParams;

#define kDfgChunkSamples 4096u

// One sample-table entry (IBL_DFG_SAMPLE_FLOATS floats): unit-disk points for the specular VNDF sample (xy)
// and for the cosine-weighted diffuse sample (zw), decorrelated by frac(u + 0.5) as in Listing 18. They
// depend only on the sample index, so the host computes them once per sample count.
#define IBL_DFG_SAMPLE_FLOATS 4
IBL_FN float4 dfgSampleEntry(uint i, uint sampleCount) {
    float2 u = hammersley(i, sampleCount);
    float2 w = make_float2(u.x + 0.5f, u.y + 0.5f);
    w = w - make_float2(floor(w.x), floor(w.y));
    float2 specular = unitDiskPoint(u), diffuse = unitDiskPoint(w);
    return make_float4(specular.x, specular.y, diffuse.x, diffuse.y);
}

// LUT axes (docs/conventions.md): x <-> NoV = (x + 0.5) / N, y <-> perceptual roughness (y + 0.5) / N.
IBL_FN float dfgTexelCenter(uint i, uint size) {
    return ((float)i + 0.5f) / (float)size;
}

// One specular sample: the visible normal of the unit-disk point (diskX, diskY) for the view v
// (NoV = v.z); returns its estimator weight G2/G1(V) (x) and its Fresnel factor Fc = (1 - VoH)^5 (y).
IBL_FN float2 dfgSpecularSample(vec3 v, VndfView view, float alpha, float invG1V, float diskX, float diskY) {
    vec3 h = vndfSample(view, diskX, diskY);
    float VoH = saturate(v3dot(v, h));
    float NoL = 2.0f * VoH * h.z - v.z; // z of reflect(v, h)
    return make_float2(G_SmithGGXCorrelated(v.z, fmax(NoL, 0.0f), alpha) * invG1V, pow5(1.0f - VoH));
}

// One diffuse sample: Fr_DisneyDiffuse for the cosine-sampled light of the unit-disk point (diskX, diskY).
IBL_FN float dfgDiffuseSample(vec3 v, float perceptualRoughness, float diskX, float diskY) {
    vec3 l = cosineSampleFromDisk(diskX, diskY);
    float LoH = sqrt(0.5f * (1.0f + v3dot(v, l))); // cos of the half angle between v and l
    return Fr_DisneyDiffuse(v.z, l.z, LoH, perceptualRoughness);
}

// Returns the sums of (DFG1, DFG2, Disney) over samples [firstSample, endSample) for one (NoV,
// perceptual roughness) from the sample table. Callers sum chunks of at most
// kDfgChunkSamples in fp32 and divide by the sample count: chunking bounds the fp32 rounding of a
// mean over millions of samples to about 1e-6 while the loop stays simple enough to vectorize.
// Specular: visible normals are importance sampled (Heitz 2018); that estimator of the directional
// albedo is G2/G1(V), the same expectation as Listing 18's GVis under NDF sampling with far less
// variance. DFG1 = E[(1 - Fc) G2/G1], DFG2 = E[Fc G2/G1], Fc = (1 - VoH)^5.
// Diffuse: E[Fr_DisneyDiffuse] under cosine sampling (Listing 18: the pdf cancels the 1/pi and NoL).
// The C++ build vectorizes the sample loop across samples (IBL_SIMD_SUM). For that its body declares no
// vec3 (GCC gives every struct declared in an OpenMP SIMD loop a per-lane array, and does not vectorize
// one of 3 floats; one of 2 it does) and its index is an int (4 * i of a uint may wrap, which hides the
// stride from GCC).
IBL_FN vec3 integrateDfgChunk(float NoV, float perceptualRoughness, IBL_GLOBAL const float* table,
                              uint firstSample, uint endSample) {
    float alpha = alphaFromPerceptual(perceptualRoughness);
    NoV = clamp(NoV, 1e-4f, 1.0f);
    vec3 v = v3(sqrt(1.0f - NoV * NoV), 0.0f, NoV);
    VndfView view = vndfPrepareXZ(v, alpha);
    float invG1V = 1.0f / G1_SmithGGX(NoV, alpha);

    float dfg1 = 0.0f, dfg2 = 0.0f, diffuse = 0.0f;
    const IBL_GLOBAL float* chunk = table + IBL_DFG_SAMPLE_FLOATS * firstSample;
    int count = (int)(endSample - firstSample);
    IBL_SIMD_SUM(dfg1, dfg2, diffuse)
    for (int i = 0; i < count; ++i) {
        IBL_UNIFORM_LOOP_HEAD();
        const IBL_GLOBAL float* e = chunk + IBL_DFG_SAMPLE_FLOATS * i;
        float2 specular = dfgSpecularSample(v, view, alpha, invG1V, e[0], e[1]); // (G2/G1, Fc)
        dfg1 += (1.0f - specular.y) * specular.x;
        dfg2 += specular.y * specular.x;
        diffuse += dfgDiffuseSample(v, perceptualRoughness, e[2], e[3]);
    }
    return v3(dfg1, dfg2, diffuse);
}

// The work-items of dfg.cl, one LUT texel (iblbake/opencl/dispatch.h). dfgChunkItem stores the sums of one
// chunk of samples: a plain store, as reading the output here (+=) stops PoCL from vectorizing the sample
// loop; dfgAddChunkItem adds a chunk stored so into the running sums.
IBL_FN void dfgChunkItem(WorkItem t, IBL_GLOBAL float* out, DfgParams params, IBL_GLOBAL const float* table) {
    storeTexel(out, t,
               integrateDfgChunk(dfgTexelCenter(t.x, params.size), dfgTexelCenter(t.y, params.size), table,
                                 params.firstSample, params.endSample));
}

IBL_FN void dfgAddChunkItem(WorkItem t, IBL_GLOBAL float* out, DfgParams params,
                            IBL_GLOBAL const float* chunk) {
    addToTexel(out, t, loadTexel(chunk, t));
}

IBL_END_NAMESPACE

#endif
