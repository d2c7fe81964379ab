// BRDF terms of the Frostbite/Filament standard material (Frostbite 2014 section 3.1, Filament 4.4-4.6).
// Roughness naming: `perceptualRoughness` is what artists set (Frostbite's linearRoughness);
// `alpha` = perceptualRoughness^2 is the GGX parameter (docs/conventions.md, Roughness).
#ifndef IBL_BRDF_H
#define IBL_BRDF_H

#include "portable.h"

IBL_BEGIN_NAMESPACE

IBL_FN float alphaFromPerceptual(float perceptualRoughness) {
    return perceptualRoughness * perceptualRoughness;
}

// GGX / Trowbridge-Reitz NDF including the 1/pi (Frostbite Listing 2 omits it; we keep D normalized
// so that pdfs built from it integrate to one).
IBL_FN float D_GGX(float NoH, float alpha) {
    float a2 = alpha * alpha;
    float f = (NoH * a2 - NoH) * NoH + 1.0f;
    return a2 / (IBL_PI * f * f);
}

// sqrt(alpha^2 + (1 - alpha^2) cos^2): the shared factor of the Smith Lambda terms (Frostbite eq. 3
// rewritten as Lambda(x) = (s(x)/cos(x) - 1) / 2), finite for cos = 0.
IBL_FN float smithFactor(float cosTheta, float alpha) {
    float a2 = alpha * alpha;
    return sqrt(a2 + (1.0f - a2) * cosTheta * cosTheta);
}

// Height-correlated Smith masking-shadowing G2 (Frostbite eq. 3), written without divisions by the cosines.
IBL_FN float G_SmithGGXCorrelated(float NoV, float NoL, float alpha) {
    float denom = NoL * smithFactor(NoV, alpha) + NoV * smithFactor(NoL, alpha);
    return denom > 0.0f ? 2.0f * NoV * NoL / denom : 0.0f;
}

// Smith masking G1 of one direction.
IBL_FN float G1_SmithGGX(float NoX, float alpha) {
    float denom = NoX + smithFactor(NoX, alpha);
    return denom > 0.0f ? 2.0f * NoX / denom : 0.0f;
}

// Visibility V = G2 / (4 NoL NoV), height-correlated (Frostbite Listing 2, Filament 4.4.2).
IBL_FN float V_SmithGGXCorrelated(float NoV, float NoL, float alpha) {
    float denom = NoL * smithFactor(NoV, alpha) + NoV * smithFactor(NoL, alpha);
    return denom > 0.0f ? 0.5f / denom : 0.0f;
}

// Schlick Fresnel with an explicit f90 (Frostbite Listing 1, eq. 54).
IBL_FN float F_Schlick(float f0, float f90, float u) {
    return f0 + (f90 - f0) * pow5(1.0f - u);
}
IBL_FN float3 F_Schlick3(float3 f0, float f90, float u) {
    return f0 + (make_float3(f90, f90, f90) - f0) * pow5(1.0f - u);
}

// Renormalized Disney diffuse without the 1/pi (Frostbite Listing 1). It takes the perceptual roughness.
IBL_FN float Fr_DisneyDiffuse(float NoV, float NoL, float LoH, float perceptualRoughness) {
    float energyBias = mix(0.0f, 0.5f, perceptualRoughness);
    float energyFactor = mix(1.0f, 1.0f / 1.51f, perceptualRoughness);
    float fd90 = energyBias + 2.0f * LoH * LoH * perceptualRoughness;
    float lightScatter = F_Schlick(1.0f, fd90, NoL);
    float viewScatter = F_Schlick(1.0f, fd90, NoV);
    return lightScatter * viewScatter * energyFactor;
}

// Multiple-scattering energy compensation from the DFG LUT (Filament 4.7.2). Filament's r, the
// single-scattering directional albedo for f0 = f90 = 1, is DFG1 + DFG2 in our LUT layout.
IBL_FN float3 energyCompensation(float3 f0, float dfg1, float dfg2) {
    float r = fmax(dfg1 + dfg2, 1e-4f);
    return make_float3(1.0f, 1.0f, 1.0f) + f0 * (1.0f / r - 1.0f);
}

// GGX D with 1 - NoH^2 taken as |N x H|^2 (Filament's precise form): near the peak of a lobe as narrow
// as the sun's, 1 - NoH^2 in fp32 loses all but a few bits to cancellation.
IBL_FN float D_GGXFromCross(vec3 NxH, float NoH, float alpha) {
    float a = NoH * alpha;
    float d = v3dot(NxH, NxH) + a * a; // 0 only for H = -N (NoH saturated to 0): no microfacet there
    float k = d > 0.0f ? alpha / d : 0.0f;
    return k * k * IBL_INV_PI;
}

IBL_FN vec3 fresnelSchlickRgb(vec3 f0, float f90, float LoH) {
    float fc = pow5(1.0f - LoH);
    return v3(f0.x + (f90 - f0.x) * fc, f0.y + (f90 - f0.y) * fc, f0.z + (f90 - f0.z) * fc);
}

IBL_END_NAMESPACE

#endif
