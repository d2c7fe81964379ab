// The shading point and the runtime's evaluation switches (RuntimeParams.flags), which the probes (probe.h)
// and the area lights (area_lights.h) read alike.
#ifndef IBL_SHADING_POINT_H
#define IBL_SHADING_POINT_H

#include "portable.h"

IBL_BEGIN_NAMESPACE

// Evaluation switches (RuntimeParams.flags).
#define IBL_RT_SPECULAR (1u << 0)            // specular from the probes
#define IBL_RT_DIFFUSE (1u << 1)             // diffuse from the SH coefficients
#define IBL_RT_ENERGY_COMPENSATION (1u << 2) // Filament 4.7.2
#define IBL_RT_DISNEY_DIFFUSE (1u << 3)      // diffuse times the LUT's Disney term (else Lambert)
#define IBL_RT_SPECULAR_DOMINANT (1u << 4)   // specularDominantDirection (else the mirror direction)
#define IBL_RT_DIFFUSE_DOMINANT (1u << 5)    // Listing 23 (else the normal)
#define IBL_RT_SPECULAR_OCCLUSION (1u << 6)  // Listing 26 from the point's ao
#define IBL_RT_HORIZON_OCCLUSION (1u << 7)   // Filament 5.6.2.1
#define IBL_RT_DISTANCE_ROUGHNESS (1u << 8)  // Listing 25 for local probes
#define IBL_RT_SUN (1u << 9)                 // the sun disk light
#define IBL_RT_F90_FROM_F0 (1u << 10) // f90 = saturate(50 * 0.33 * (f0.r + f0.g + f0.b)) (Filament 5.6.2)
#define IBL_RT_SH_OVER_PI (1u << 11)  // the SH evaluates to E / pi (Lambert folded in) instead of E
#define IBL_RT_SUN_NORMALIZATION (1u << 12) // (alpha / alpha')^2 on the sun's representative-point GGX
#define IBL_RT_IRRADIANCE_CUBE (1u << 13)   // diffuse from the irradiance cube (E / pi) instead of the SH
#define IBL_RT_SUN_QUADRATURE (1u << 14)    // sun specular integrated over the disk, not Listing 6's point
// The distant LD chain's level 0 still holds the sun (the unconvolved source; the extraction's residual
// from level 1 on): where the lookup reads level 0 with trilinear weight w0, the disk's specular gets 1 - w0,
// so a mirror shows the sun's own pixels and every roughness counts the sun once.
#define IBL_RT_SUN_IN_LEVEL0 (1u << 15)
// The distant LD from the fitted taps of specular_taps.h (probe.h distantSpecularLd), else one read at the
// dominant direction (the split sum's).
#define IBL_RT_SPECULAR_TAPS (1u << 16)

// A shading point. view points from the surface toward the eye (Filament's v); neither vector has to be
// normalized (a zero normal becomes +Y, a zero view the normal).
IBL_STRUCT(ShadingPoint) {
    vec3 position;
    vec3 normal;
    vec3 view;
    vec3 baseColor;
    float metallic;
    float perceptualRoughness;
    float ao;
};

IBL_END_NAMESPACE

#endif
