// One bright texel of ld.h's bright pass for the lobe around one direction: integral_texel D(h) NoL dl at its
// point value, on a sub-grid, or in closed form (narrow_lobe.h); and the patch of an output texel's footprint
// that footprint_lanes.h's scalar loop sums.
#ifndef IBL_BRIGHT_TEXEL_H
#define IBL_BRIGHT_TEXEL_H

#include "brdf.h"
#include "cube.h"
#include "narrow_lobe.h"
#include "sampling.h"

IBL_BEGIN_NAMESPACE

// D(h) NoL over a sub-rectangle [u0, u0 + step] x [v0, v0 + step] (face-plane coordinates in [-1, 1])
// of one face, evaluated at its centre with its solid angle.
IBL_FN float lobeWeightOfPatch(vec3 n, int face, float u0, float v0, float step, float alpha) {
    float omega = cubePatchSolidAngle(u0, v0, step);
    vec3 l = v3normalize(
        cubeFaceDirection(face, 0.5f * (u0 + 0.5f * step + 1.0f), 0.5f * (v0 + 0.5f * step + 1.0f)));
    float NoL = v3dot(n, l);
    vec3 h = v3normalize(v3add(n, l));
    return NoL > 0.0f ? D_GGX(v3dot(n, h), alpha) * NoL * omega : 0.0f;
}

// The angle between two unit directions whose cosine is cosAngle, as their chord: accurate where it matters
// (small angles), and no acos.
IBL_FN float chordAngle(float cosAngle) {
    return sqrt(fmax(0.0f, 2.0f - 2.0f * cosAngle));
}

// integral_texel D(h) NoL dl of one bright-list entry for the lobe around n (unnormalized).
IBL_FN_INLINED float brightTexelWeight(vec3 n, Frame frame, IBL_GLOBAL const float* e, float alpha,
                                       float texelSize) {
    // The midpoint rule over a texel of size a at angle theta from the lobe centre errs by about
    // (a / theta)^2 in GGX's theta^-4 tail, so texels nearer than 10 texels are integrated on an S x S
    // grid, S = 10 a / max(theta, alpha) (error ~1%). Near a lobe under a quarter texel wide the closed
    // form is used instead (narrowLobeClosedFormApplies).
    vec3 d = v3(e[0], e[1], e[2]);
    float cosAngle = v3dot(n, d);
    float angle = chordAngle(cosAngle);
    float subdivisions = ceil(10.0f * texelSize / fmax(angle, alpha));
    int face = (int)e[7];
    float u0 = -1.0f + e[8] * texelSize, v0 = -1.0f + e[9] * texelSize;
    if (narrowLobeClosedFormApplies(alpha, texelSize, angle))
        return narrowLobeTexelWeight(frame, face, u0, v0, texelSize, alpha);
    if (subdivisions <= 1.0f || cosAngle < 0.0f) {
        vec3 h = v3normalize(v3add(n, d));
        return cosAngle > 0.0f ? D_GGX(v3dot(n, h), alpha) * cosAngle * e[3] : 0.0f;
    }
    int S = (int)fmin(subdivisions, 32.0f);
    float step = texelSize / (float)S, weight = 0.0f;
    for (int j = 0; j < S; ++j)
        for (int k = 0; k < S; ++k)
            weight += lobeWeightOfPatch(n, face, u0 + (float)k * step, v0 + (float)j * step, step, alpha);
    return weight;
}

// Patch (j, k) of an S x S grid of step `step` over the output texel at (u0, v0) of `face`: its solid angle
// times the lobe around its centre over bright entry e (brightTexelWeight).
IBL_FN float footprintPatchWeight(int face, float u0, float v0, float step, int j, int k,
                                  IBL_GLOBAL const float* e, float alpha, float sourceTexelSize) {
    float pu = u0 + (float)k * step, pv = v0 + (float)j * step;
    vec3 n = v3normalize(
        cubeFaceDirection(face, 0.5f * (pu + 0.5f * step + 1.0f), 0.5f * (pv + 0.5f * step + 1.0f)));
    return cubePatchSolidAngle(pu, pv, step) *
           brightTexelWeight(n, frameFromNormal(n), e, alpha, sourceTexelSize);
}

IBL_END_NAMESPACE

#endif
