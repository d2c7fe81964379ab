// The runtime's multi-tap specular lookup: IBL_SPECULAR_TAP_COUNT reads of the LD chain (and its rough
// layers) in the plane of incidence whose weighted sum stands for the lobe the view sees, f(v, l) <n.l>,
// where the split sum's single read stands for the N = V = R lobe it was prefiltered with
// (docs/conventions.md "The runtime's lookup direction"). The taps' directions, lookup roughnesses and
// weights are fitted offline (tools/specular_taps) and read bilinearly from specular_taps_table.h over (NoV,
// r).
#ifndef IBL_SPECULAR_TAPS_H
#define IBL_SPECULAR_TAPS_H

#include "portable.h"
#include "specular_taps_table.h"

IBL_BEGIN_NAMESPACE

IBL_STRUCT(SpecularTap) {
    float lerpFactor;          // the direction normalize(lerp(N, R, lerpFactor))
    float perceptualRoughness; // the roughness the LD is read at
    float weight;              // the taps' weights sum to 1
};

// Tap `tap` for a view at NoV on a surface of perceptual roughness r: the table's four cells around (NoV, r),
// bilinear (cells at NoV, r = i / (grid - 1), j / (grid - 1)).
IBL_FN SpecularTap specularTap(float NoV, float perceptualRoughness, uint tap) {
    float last = IBL_FLOAT(IBL_SPECULAR_TAP_GRID - 1u);
    float r = saturate(perceptualRoughness);
    float x = saturate(NoV) * last, y = r * last;
    float x0f = fmin(floor(x), last - 1.0f), y0f = fmin(floor(y), last - 1.0f);
    float fx = x - x0f, fy = y - y0f;
    uint cellFloats = 3u * IBL_SPECULAR_TAP_COUNT;
    uint c00 = (IBL_UINT(y0f) * IBL_SPECULAR_TAP_GRID + IBL_UINT(x0f)) * cellFloats + 3u * tap;
    uint c10 = c00 + cellFloats, c01 = c00 + IBL_SPECULAR_TAP_GRID * cellFloats, c11 = c01 + cellFloats;
    float w00 = (1.0f - fx) * (1.0f - fy), w10 = fx * (1.0f - fy), w01 = (1.0f - fx) * fy, w11 = fx * fy;
    SpecularTap t;
    t.lerpFactor = w00 * kSpecularTapTable[c00] + w10 * kSpecularTapTable[c10] +
                   w01 * kSpecularTapTable[c01] + w11 * kSpecularTapTable[c11];
    float ratio = w00 * kSpecularTapTable[c00 + 1u] + w10 * kSpecularTapTable[c10 + 1u] +
                  w01 * kSpecularTapTable[c01 + 1u] + w11 * kSpecularTapTable[c11 + 1u];
    t.perceptualRoughness = saturate(ratio * r);
    t.weight = w00 * kSpecularTapTable[c00 + 2u] + w10 * kSpecularTapTable[c10 + 2u] +
               w01 * kSpecularTapTable[c01 + 2u] + w11 * kSpecularTapTable[c11 + 2u];
    return t;
}

IBL_END_NAMESPACE

#endif
