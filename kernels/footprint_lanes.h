// For brightFootprintWeight (bright_entry_weight.h): footprintPatchesWeight with IBL_LANES patches of the
// output texel in the lanes of float8 vectors (lanes.h): brightTexelWeight around each patch centre, its
// point value or its sub-grid of lobeWeightOfPatch (each lane's own size; the lanes run the largest and mask
// the rest). This was most of the bright pass of a 32 px level (49 patches per bright texel within three
// texels, up to 4 x 4 sub-patches each). When a lane could take brightTexelWeight's closed form (lobes under
// a quarter source texel: tiny faces only) the scalar loop runs instead.
#ifndef IBL_FOOTPRINT_LANES_H
#define IBL_FOOTPRINT_LANES_H

#include "bright_texel.h"
#include "lanes.h"

IBL_BEGIN_NAMESPACE

// D_GGX in every lane.
IBL_FN float8 dGgxLanes(float8 NoH, float alpha) {
    float a2 = alpha * alpha;
    float8 f = (NoH * a2 - NoH) * NoH + 1.0f;
    return a2 / (IBL_PI * f * f);
}

// brightTexelWeight's first test in every lane, for bright texels (face-plane size texelSize) at cosine
// cosAngle from the lobe centre: their chord angle and sub-grid size (into *angle and *subdivisions), and
// whether they take the point value (one sub-patch, or behind the lobe). The closed form is the caller's.
IBL_FN int8 brightPointValueLanes(float8 cosAngle, float alpha, float texelSize, float8* angle,
                                  float8* subdivisions) {
    *angle = sqrt(fmax(0.0f, 2.0f - 2.0f * cosAngle)); // chordAngle
    *subdivisions = ceil(10.0f * texelSize / fmax(*angle, alpha));
    return islessequal(*subdivisions, 1.0f) | isless(cosAngle, 0.0f);
}

// brightTexelWeight's point value in every lane: D(h) NoL times the solid angle of a bright texel in unit
// direction d, for the lobe around unit direction n, with cosAngle = n.d.
IBL_FN float8 brightPointWeightLanes(float8 nx, float8 ny, float8 nz, float8 dx, float8 dy, float8 dz,
                                     float8 cosAngle, float8 solidAngle, float alpha) {
    float8 hx = nx + dx, hy = ny + dy, hz = nz + dz;
    float8 invH = 1.0f / sqrt(hx * hx + hy * hy + hz * hz);
    float8 NoH = nx * (hx * invH) + ny * (hy * invH) + nz * (hz * invH);
    return select((float8)0.0f, dGgxLanes(NoH, alpha) * cosAngle * solidAngle, isgreater(cosAngle, 0.0f));
}

// lobeWeightOfPatch(n, face, u0, v0, step, alpha) in every lane.
IBL_FN float8 lobeWeightOfPatchLanes(float8 nx, float8 ny, float8 nz, int face, float8 u0, float8 v0,
                                     float8 step, float alpha) {
    float8 omega = cubePatchSolidAngleLanes(u0, v0, step);
    float8 lx, ly, lz;
    cubeFaceDirectionLanes(face, 0.5f * (u0 + 0.5f * step + 1.0f), 0.5f * (v0 + 0.5f * step + 1.0f), &lx, &ly,
                           &lz);
    float8 inv = 1.0f / sqrt(lx * lx + ly * ly + lz * lz);
    lx *= inv, ly *= inv, lz *= inv;
    float8 NoL = nx * lx + ny * ly + nz * lz;
    float8 hx = nx + lx, hy = ny + ly, hz = nz + lz;
    float8 invH = 1.0f / sqrt(hx * hx + hy * hy + hz * hz);
    float8 NoH = nx * (hx * invH) + ny * (hy * invH) + nz * (hz * invH);
    return select((float8)0.0f, dGgxLanes(NoH, alpha) * NoL * omega, isgreater(NoL, 0.0f));
}

// The sum of footprintPatchWeight over the S x S grid, with the patches in vector lanes.
IBL_FN float footprintPatchesWeight(int face, float u0, float v0, float step, int S,
                                    IBL_GLOBAL const float* e, float alpha, float sourceTexelSize) {
    if (4.0f * alpha < sourceTexelSize) { // narrowLobeClosedFormApplies may hold for some patch
        float weight = 0.0f;
        for (int j = 0; j < S; ++j)
            for (int k = 0; k < S; ++k)
                weight += footprintPatchWeight(face, u0, v0, step, j, k, e, alpha, sourceTexelSize);
        return weight;
    }
    int brightFace = (int)e[7];
    float bu0 = -1.0f + e[8] * sourceTexelSize, bv0 = -1.0f + e[9] * sourceTexelSize;
    float8 sum = 0.0f;
    for (int first = 0; first < S * S; first += (int)IBL_LANES) {
        PatchLanes p = patchLanes(face, u0, v0, step, S, first);
        float8 nx = p.nx, ny = p.ny, nz = p.nz;
        // brightTexelWeight(n, ..., e): the point value where one sub-patch suffices or e is behind n.
        float8 cosAngle = nx * e[0] + ny * e[1] + nz * e[2];
        float8 angle, subdivisions;
        int8 point = brightPointValueLanes(cosAngle, alpha, sourceTexelSize, &angle, &subdivisions);
        float8 pointWeight = brightPointWeightLanes(nx, ny, nz, e[0], e[1], e[2], cosAngle, e[3], alpha);
        // Else the lane's own S x S sub-grid of the bright texel.
        int8 sub = select(convert_int8(fmin(subdivisions, 32.0f)), (int8)0, point);
        int subMax = maxLane(sub);
        float8 subStep = sourceTexelSize / convert_float8(max(sub, 1));
        float8 subWeight = 0.0f;
        for (int j = 0; j < subMax; ++j)
            for (int k = 0; k < subMax; ++k) {
                float8 w = lobeWeightOfPatchLanes(nx, ny, nz, brightFace, bu0 + (float)k * subStep,
                                                  bv0 + (float)j * subStep, subStep, alpha);
                subWeight += select((float8)0.0f, w, ((int8)j < sub) & ((int8)k < sub));
            }
        sum += select((float8)0.0f, p.solidAngle * select(subWeight, pointWeight, point), p.inGrid);
    }
    return sumLanes(sum);
}

IBL_END_NAMESPACE

#endif
