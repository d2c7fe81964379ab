// The weight of one bright-list entry for one output texel of ld.h's bright pass: at the texel's centre
// (bright_texel.h), or averaged over its footprint where the lobe is narrower than the texel, with the
// footprint's patches in lanes (narrow_lobe_lanes.h, footprint_lanes.h).
#ifndef IBL_BRIGHT_ENTRY_WEIGHT_H
#define IBL_BRIGHT_ENTRY_WEIGHT_H

#include "bright_texel.h"
#include "cube.h"
#include "footprint_lanes.h"
#include "narrow_lobe.h"
#include "narrow_lobe_lanes.h"
#include "sampling.h"

IBL_BEGIN_NAMESPACE

// Footprint-averaged bright texels. Where the lobe is narrower than an output texel, LD at the texel centre
// sees a sub-texel sun or misses it: a level's energy then depends on where the sun falls (at a cube edge /
// corner, 0.50 / 1.36 of the source's at 64 px) and a rotating map pulses. Such a texel t stores LD averaged
// over its own solid angle Omega_t instead, whose bright part is
//   sum_b B_b integral_b G_t(l) dl / (Omega_t W),  G_t(l) = integral_t D(h) (n.l) dn,
// since D(h) (n.l), h = normalize(n + l), is symmetric in n and l: G_t is the lobe around l integrated over
// the output texel, and summed over every t it is W for every l, so a level keeps its source's energy.
// "Narrower": the lobe's reflected directions (about 2 alpha wide) under one texel (2 / n face-plane units).
IBL_FN bool ldFootprintApplies(float alpha, uint outputFaceSize) {
    return 2.0f * alpha < 2.0f / (float)outputFaceSize;
}

// The angle from unit direction n to bright entry e's centre (chordAngle).
IBL_FN float brightEntryAngle(vec3 n, IBL_GLOBAL const float* e) {
    return chordAngle(v3dot(n, v3(e[0], e[1], e[2])));
}

// Whether LD averaged over output texel t's footprint (face-plane size outSize) needs more than its value at
// t's centre for bright entry e at `angle` from it: within three texels of t. Farther, the average is the
// centre's value.
IBL_FN bool brightEntryNearFootprint(float angle, float outSize) {
    return angle < 3.0f * outSize;
}

// integral_b G_t(l) dl for bright entry e within three texels of output texel t (face, corner (u0, v0),
// face-plane size outSize, e's centre at `angle` from t's centre).
// - With a lobe under a quarter of t: b in S x S patches, each its solid angle times
//   narrowLobeTexelWeight's closed form of G_t around its centre; G_t varies over about alpha near t's
//   edges, so S = 4 source texel / alpha, up to 16, for the bright texels within about a texel of t (the
//   midpoint rule converges only linearly across an edge it does not resolve: up to 8, the texels beside
//   a sun on rooitou's 32-px level 1 read 1.2% off), and 1 beyond.
// - With a wider lobe: t in S x S patches, each its solid angle times the lobe around its centre over b
//   (brightTexelWeight), S ~ 2 outSize / alpha (2 to 8).
IBL_FN float brightFootprintWeight(int face, float u0, float v0, float outSize, float angle,
                                   IBL_GLOBAL const float* e, float alpha, float sourceTexelSize) {
    if (narrowLobeClosedFormApplies(alpha, outSize, angle)) {
        // Only a bright texel touching t (or a texel away) has t's edges across it.
        int S = angle < outSize + sourceTexelSize
                    ? (int)clamp(ceil(4.0f * sourceTexelSize / alpha), 1.0f, 16.0f)
                    : 1;
        int sourceFace = (int)e[7];
        float step = sourceTexelSize / (float)S;
        float bu = -1.0f + e[8] * sourceTexelSize, bv = -1.0f + e[9] * sourceTexelSize;
        return narrowFootprintPatchesWeight(faceSquareCorners(face, u0, v0, outSize), sourceFace, bu, bv,
                                            step, S, alpha);
    }
    int S = (int)clamp(ceil(2.0f * outSize / alpha), 2.0f, 8.0f);
    return footprintPatchesWeight(face, u0, v0, outSize / (float)S, S, e, alpha, sourceTexelSize);
}

// An output texel of the bright pass: its centre direction and frame, and its square (face, corner (u0, v0),
// face-plane size) with whether LD is averaged over it (ldFootprintApplies).
typedef struct {
    vec3 centre;
    Frame frame;
    int face;
    float u0, v0, size;
    int footprint;
    float solidAngle; // Omega_t, or -1 until a bright entry near the footprint needs it
} BrightTarget;

// The weight of bright entry e for output texel t (brightTexelsLd divides it by W).
IBL_FN float brightEntryWeight(BrightTarget* t, IBL_GLOBAL const float* e, float alpha, float texelSize) {
    float angle = t->footprint ? brightEntryAngle(t->centre, e) : 0.0f;
    if (t->footprint && brightEntryNearFootprint(angle, t->size)) {
        // Omega_t when an entry is first near the footprint (few texels have one; four atan2).
        if (t->solidAngle < 0.0f) t->solidAngle = cubePatchSolidAngle(t->u0, t->v0, t->size);
        return brightFootprintWeight(t->face, t->u0, t->v0, t->size, angle, e, alpha, texelSize) /
               t->solidAngle;
    }
    // No footprint, or one whose average over t is the value at its centre.
    return brightTexelWeight(t->centre, t->frame, e, alpha, texelSize);
}

IBL_END_NAMESPACE

#endif
