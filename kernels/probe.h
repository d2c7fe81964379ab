// Runtime probe sampling: shading a point with the baked products (docs/conventions.md "The runtime's
// lookup direction", baker/runtime/README.md). One source for the C++ runtime (CPU evaluation) and the
// OpenCL kernel (runtime.cl).
//   distant probe  LD cube chain sampled trilinearly (cubeSampleLod, the bake's bordered pyramid) at the
//                  LOD of the chain's roughness mapping; DFG LUT bilinear; Listing 24 / Filament evaluateIBL
//   energy         Filament 4.7.2 compensation 1 + f0 (1 / r - 1), r = DFG1 + DFG2
//   diffuse        Filament irradianceSH * Lambert, or times the LUT's Disney term (Listing 24)
//   directions     specular dominant direction (Listing 22 and the lobe's mean), optional diffuse one
//                  (Listing 23); the distant probe's LD from fitted taps in the plane of incidence
//                  (specular_taps.h, IBL_RT_SPECULAR_TAPS) instead of one read
//   occlusion      specular occlusion (Listing 26), horizon occlusion (Filament 5.6.2.1)
//   local probes   parallax correction and distance-based roughness (parallax.h, Appendix F), composed
//                  with the distant probe by the alpha rule of Frostbite 4.9.5; alpha = influence weight
//                  x the probe's texel visibility (4.9.1.2) where the probe has one
//   sun            disk light of Listing 6: punctual for diffuse, representative point for specular
// Roughness naming (docs/conventions.md): `perceptualRoughness` r is what artists set, `alpha` = r^2.
// Frostbite's listings call r "linearRoughness" and alpha "roughness"; Listings 22, 23 and 26 take alpha.
#ifndef IBL_PROBE_H
#define IBL_PROBE_H

#include "area_lights.h" // part of the runtime (and of probe.glsl); shadePoint does not call it
#include "brdf.h"
#include "cube_sample.h"
#include "mip_mapping.h"
#include "parallax.h"
#include "sampling.h"
#include "shading_point.h"
#include "specular_taps.h"

#ifdef __cplusplus
IBL_BEGIN_NAMESPACE
using std::exp2;
using std::pow;
IBL_END_NAMESPACE
#endif

IBL_BEGIN_NAMESPACE

// One LD chain inside a float buffer that may hold several (local probes share one buffer).
IBL_STRUCT(LdChain) {
    CubePyramidLayout shape; // bordered pyramid (cube_sample.h); levelCount = the chain's levels
    uint32_t dataOffset;     // first float of this pyramid in its buffer
    uint32_t mapping;        // IBL_MIP_* (mip_mapping.h)
};

// A chain's rough layers (mip_mapping.h IBL_ROUGH_LAYER_*) in the same buffer: layerCount one-level bordered
// cubes of faceSize texels from dataOffset on, each cubePyramidFloatCount({faceSize, 1}) floats apart.
// layerCount 0: none, the chain alone.
IBL_STRUCT(RoughLayers) {
    uint32_t faceSize;
    uint32_t layerCount;
    uint32_t dataOffset;
};

// Pre-scaled SH L2 irradiance (docs/conventions.md order, 9 RGB coefficients, coefficient i's RGB at
// 3i..3i+2).
IBL_STRUCT(ShIrradiance) {
    float c[27];
};

// A distant disk light (Frostbite 4.6): illuminance * color is the RGB illuminance (lux) on a surface
// facing it.
IBL_STRUCT(SunDisk) {
    vec3 direction;      // unit, toward the light
    float angularRadius; // radians
    vec3 color;          // linear RGB, luminance 1
    float illuminance;   // E_perp, lux
};

IBL_STRUCT(LocalProbe) {
    LdChain ld;            // in the local-probe LD buffer
    ProbeVolume proxy;     // re-projection geometry
    ProbeVolume influence; // where the probe applies
    vec3 captureOffset;    // capture point = proxy.center + offset along the proxy's axes
    float fadeDistance;    // soft transition width inside the influence boundary
    // Texel visibility (Frostbite 4.9.1.2, "the visibility of surrounding objects into the alpha channel"):
    // when hasVisibility != 0, a scalar pyramid of the LD chain's layout at visibilityOffset in the local
    // buffer (cubeSampleLodScalar), and the LD chain holds colour x visibility (premultiplied). 0: every
    // texel visible, the LD chain is the colour, the probe composes as by influence alone.
    uint32_t hasVisibility;
    uint32_t visibilityOffset;
};

// Everything of one evaluation that is the same for every point (a kernel argument by value: 4-byte
// scalars only, identical layout in C++ and OpenCL C).
IBL_STRUCT(RuntimeParams) {
    uint32_t flags;           // IBL_RT_*
    uint32_t dfgSize;         // N of the N x N DFG LUT (3 floats per texel: DFG1, DFG2, Disney)
    uint32_t localProbeCount; // in evaluation order (smallest influence first)
    uint32_t pointCount;
    LdChain distant;
    SunDisk sun;
    float dielectricF0; // f0 of a non-metal (0.04: Filament's reflectance 0.5)
    ShIrradiance sh;
    // One bordered level of E / pi in the distant buffer after the LD pyramid (IBL_RT_IRRADIANCE_CUBE):
    // the baker's irradiance cube, free of L2 SH's ringing and its limit to low frequencies.
    LdChain irradiance;
    // The distant chain's rough layers in the distant buffer (layerCount 0: none).
    RoughLayers distantRoughLayers;
};

IBL_STRUCT(ShadeResult) {
    vec3 diffuse;     // indirect diffuse + the sun's diffuse
    vec3 specular;    // indirect specular + the sun's specular
    float localAlpha; // composed alpha of the local probes (4.9.5); the distant probe got 1 - localAlpha
};

// ---------------------------------------------------------------------------------------------------
// Lookups

IBL_FN float ldLodForRoughness(LdChain ld, float perceptualRoughness) {
    return mipLevelForRoughness(ld.mapping, perceptualRoughness, ld.shape.levelCount);
}

// Trilinear LD in direction d (non-zero, need not be unit) for a perceptual roughness.
IBL_FN vec3 sampleLd(IBL_FLOAT_BUFFER data, LdChain ld, vec3 d, float perceptualRoughness) {
    return cubeSampleLod(data + ld.dataOffset, ld.shape, d, ldLodForRoughness(ld, perceptualRoughness));
}

// The rough layers' LD in direction d (non-zero, need not be unit): bilinear in the two layers around r's
// fractional layer (clamped to the layers), linear between them.
IBL_FN vec3 sampleRoughLayers(IBL_FLOAT_BUFFER data, RoughLayers layers, vec3 d, float perceptualRoughness) {
    CubePyramidLayout one;
    one.baseFaceSize = layers.faceSize;
    one.levelCount = 1u;
    uint stride = cubePyramidFloatCount(one);
    float t = clamp(roughLayerForRoughness(perceptualRoughness), 0.0f, IBL_FLOAT(layers.layerCount - 1u));
    uint k = min(IBL_UINT(t), layers.layerCount - 1u);
    uint k1 = min(k + 1u, layers.layerCount - 1u);
    float fraction = t - IBL_FLOAT(k);
    CubeCoord c = cubeCoordFromDirection(d);
    vec3 a = cubeSampleLevel(data + layers.dataOffset + k * stride, one, 0u, c);
    vec3 b = cubeSampleLevel(data + layers.dataOffset + k1 * stride, one, 0u, c);
    return v3add(v3scale(a, 1.0f - fraction), v3scale(b, fraction));
}

// LD from a chain and its rough layers: the chain up to r_0, the layers from r_1 on, blended between
// (mip_mapping.h roughLayerWeight). Without layers, or below r_0, exactly sampleLd.
IBL_FN vec3 sampleLdWithLayers(IBL_FLOAT_BUFFER data, LdChain ld, RoughLayers layers, vec3 d,
                               float perceptualRoughness) {
    float w = layers.layerCount != 0u ? roughLayerWeight(perceptualRoughness) : 0.0f;
    if (!(w > 0.0f)) return sampleLd(data, ld, d, perceptualRoughness); // NaN too: as without layers
    vec3 rough = sampleRoughLayers(data, layers, d, perceptualRoughness);
    if (w >= 1.0f) return rough;
    return v3madd(sampleLd(data, ld, d, perceptualRoughness), 1.0f - w, v3scale(rough, w));
}

// Bilinear DFG LUT (docs/conventions.md layout: x <-> NoV = (x + 0.5) / N, y <-> r = (y + 0.5) / N), clamped
// to the texel centres (so NoV < 0.5 / N reads the first column, as Listing 24's max(NdotV, 0.5 / size)).
// Returns (DFG1, DFG2, Disney).
IBL_FN vec3 dfgLookup(IBL_FLOAT_BUFFER lut, uint size, float NoV, float perceptualRoughness) {
    float n = IBL_FLOAT(size);
    float x = clamp(NoV * n - 0.5f, 0.0f, n - 1.0f),
          y = clamp(perceptualRoughness * n - 0.5f, 0.0f, n - 1.0f);
    float x0f = floor(x), y0f = floor(y);
    float fx = x - x0f, fy = y - y0f;
    uint x0 = IBL_UINT(x0f), y0 = IBL_UINT(y0f);
    uint x1 = min(x0 + 1u, size - 1u), y1 = min(y0 + 1u, size - 1u);
    uint i00 = 3u * (y0 * size + x0), i10 = 3u * (y0 * size + x1);
    uint i01 = 3u * (y1 * size + x0), i11 = 3u * (y1 * size + x1);
    return weightedRgb4(lut, i00, i10, i01, i11, (1.0f - fx) * (1.0f - fy), fx * (1.0f - fy),
                        (1.0f - fx) * fy, fx * fy);
}

// Filament's irradianceSH(n) (5.3.4.1) on the pre-scaled coefficients. Kept small and separate so that it
// can be unified with kernels/sh.h's shEvalPrescaled (same polynomials, same order).
IBL_FN vec3 irradianceSH(ShIrradiance sh, vec3 n) {
    float p[9];
    p[0] = 1.0f;
    p[1] = n.y;
    p[2] = n.z;
    p[3] = n.x;
    p[4] = n.y * n.x;
    p[5] = n.y * n.z;
    p[6] = 3.0f * n.z * n.z - 1.0f;
    p[7] = n.z * n.x;
    p[8] = n.x * n.x - n.y * n.y;
    float r = 0.0f, g = 0.0f, b = 0.0f;
    for (int i = 0; i < 9; ++i) {
        r += sh.c[3 * i] * p[i];
        g += sh.c[3 * i + 1] * p[i];
        b += sh.c[3 * i + 2] * p[i];
    }
    return v3(r, g, b);
}

// ---------------------------------------------------------------------------------------------------
// Frostbite listings

// The direction the split sum's LD is read in. The LD was prefiltered with the N = V = R kernel D(h) <n.l>
// (Frostbite 2014 4.9.2), symmetric about its axis; the lobe a view sees, f(v, l) <n.l>, is not: it leans
// toward N, the more so the rougher and the more grazing the view, and its mean lies further from R than
// its peak. Under smooth lighting the LD is best read at the lobe's mean (first moment); under a compact
// light, nearer R, where the lobe's peak is. Listing 22 fits one lerp factor by roughness alone; this reads
// halfway between it and the mean, measured on the seven shared HDRIs (256 px, sphere grid against the
// converged reference, the split sum with the exact LD, worst column over the seven): Listing 22 5.12%
// (potsdamer_platz, r = 0.7), the mean 4.80% (studio_small_03: a compact light), halfway 4.30%.
// The mean's lerp factor t (normalize(mix(N, R, t)); F = 1, height-correlated Smith) is fitted on a 32 x 32
// grid of (NoV, alpha) with weights 1 / alpha (an error in t matters in lobe widths):
// t = (1 - alpha) (1 + r q(sqrt(NoV), r)), r the perceptual roughness, q bicubic; |t - t_mean| <= 0.017,
// 0.003 on average (DominantDirection.FollowsTheLobesMeanDirection recomputes the mean and checks it).
IBL_FN float specularLobeMeanLerp(float NoV, float perceptualRoughness) {
    float r = saturate(perceptualRoughness), alpha = r * r, s = sqrt(saturate(NoV));
    float q0 = -0.359108f + r * (-5.55337f + r * (14.2191f + r * -9.24962f));
    float q1 = 5.789f + r * (-9.98173f + r * (-10.9771f + r * 18.0085f));
    float q2 = -12.5963f + r * (57.0966f + r * (-67.3942f + r * 20.3982f));
    float q3 = 7.17814f + r * (-40.5708f + r * (64.5236f + r * -30.8789f));
    float q = q0 + s * (q1 + s * (q2 + s * q3));
    return saturate((1.0f - alpha) * (1.0f + r * q));
}

// Listing 22's lerp factor (alpha = GGX roughness).
IBL_FN float specularDominantLerpListing22(float alpha) {
    float smoothness = saturate(1.0f - alpha);
    return smoothness * (sqrt(smoothness) + alpha);
}

// Halfway between Listing 22 and the lobe's mean (above). Returns a unit vector.
IBL_FN vec3 specularDominantDirection(vec3 N, vec3 R, float NoV, float perceptualRoughness) {
    float r = saturate(perceptualRoughness);
    float t = 0.5f * (specularDominantLerpListing22(r * r) + specularLobeMeanLerp(NoV, r));
    return v3safeNormalize(v3lerp(N, R, t), N);
}

// Listing 23 (alpha = GGX roughness). The result is not normalized.
IBL_FN vec3 getDiffuseDominantDir(vec3 N, vec3 V, float NdotV, float alpha) {
    float a = 1.02341f * alpha - 1.51174f;
    float b = -0.511705f * alpha + 0.755868f;
    float lerpFactor = saturate((NdotV * a + b) * alpha);
    return v3lerp(N, V, lerpFactor);
}

// Listing 26 (the corrected version of the notes' v3; alpha = GGX roughness).
IBL_FN float computeSpecOcclusion(float NdotV, float AO, float alpha) {
    return saturate(pow(NdotV + AO, exp2(-16.0f * alpha - 1.0f)) - 1.0f + AO);
}

// Filament 5.6.2.1: (min(1 + r.n, 1))^2 for the (unit) lookup direction r.
IBL_FN float horizonOcclusion(vec3 r, vec3 n) {
    float horizon = saturate(1.0f + v3dot(r, n));
    return horizon * horizon;
}

// Listing 6: the direction toward the point of the sun disk closest to R (R itself inside the disk).
IBL_FN vec3 sunSpecularDirection(SunDisk sun, vec3 R) {
    vec3 D = sun.direction;
    float r = sin(sun.angularRadius); // disk radius
    float d = cos(sun.angularRadius); // distance to disk
    float DdotR = v3dot(D, R);
    vec3 S = v3sub(R, v3scale(D, DdotR));
    // R opposite to D has no closest side: any perpendicular will do.
    vec3 Sn = v3safeNormalize(S, frameFromNormal(D).t);
    return DdotR < d ? v3normalize(v3add(v3scale(D, d), v3scale(Sn, r))) : R;
}

// Listing 6's specular: GGX at the representative point L (the disk point closest to R), per unit E_perp
// <N.D>. Listing 6 has no energy normalization ("we have not found a correct one"): the disk widens the
// highlight, so D's peak is spread over it and the lobe gains energy, without bound as alpha -> 0. With
// energyNormalization, D is scaled by (alpha / alpha')^2 with alpha' = alpha + sin(angularRadius) / 2, the
// widened lobe (Karis 2013's sphere-light normalization, its radius / distance being sin(angularRadius)
// here): a mirror facing the sun then returns the disk's radiance F E_perp / (pi sin^2 angularRadius). alpha
// >= 2e-3 (Filament's minimum roughness) keeps fp32 D finite, with or without it.
IBL_FN vec3 sunSpecularRepresentativePoint(SunDisk sun, vec3 N, vec3 V, vec3 R, float NoVc, float alpha,
                                           vec3 f0, float f90, uint energyNormalization) {
    vec3 L = sunSpecularDirection(sun, R);
    float alphaSun = fmax(alpha, 2e-3f);
    float alphaWide = fmin(alphaSun + 0.5f * sin(sun.angularRadius), 1.0f);
    float normalization = energyNormalization != 0u ? sq(alphaSun / alphaWide) : 1.0f;
    vec3 H = v3safeNormalize(v3add(V, L), N);
    float NoL = saturate(v3dot(N, L)), NoH = saturate(v3dot(N, H)), LoH = saturate(v3dot(L, H));
    float dv = D_GGXFromCross(v3cross(N, H), NoH, alphaSun) * normalization *
               V_SmithGGXCorrelated(NoVc, NoL, alphaSun);
    return v3scale(fresnelSchlickRgb(f0, f90, LoH), dv);
}

// The sun's specular integrated over the disk, per unit E_perp (IBL_RT_SUN_QUADRATURE): the GGX BRDF x NoL
// at IBL_SUN_POINTS points of a Fibonacci spiral on the disk's tangent plane (equal areas, each carrying
// E_perp / IBL_SUN_POINTS). Where the lobe is narrower than the points' spacing, D's alpha is widened to
// half that spacing: such a lobe then still integrates to the part of it inside the disk (a mirror facing
// the disk returns F times the disk's radiance), which Listing 6's single point cannot do without a
// normalization guess. Measured against the uniform disk (tests/test_runtime_accuracy.cpp "Sun"), metal
// spheres at r = 0.1: 0.36% for the real sun, 3.3% for a 1.6-degree disk, where the normalized
// representative point is off by 10.9% and 19.7%; 16 points: 1.0% and 12%, 64: 0.2% and 1.6%.
#define IBL_SUN_POINTS 32u
IBL_FN vec3 sunSpecularQuadrature(SunDisk sun, vec3 D, vec3 N, vec3 V, float NoVc, float alpha, vec3 f0,
                                  float f90) {
    Frame frame = frameFromNormal(D);
    float radius = tan(sun.angularRadius);
    float alphaV = fmax(alpha, 2e-3f);
    float alphaD = fmax(alphaV, 0.5f * radius * sqrt(IBL_PI / IBL_FLOAT(IBL_SUN_POINTS))); // half the spacing
    float c = 1.0f, s = 0.0f; // the golden angle's rotation, applied k times
    vec3 sum = v3(0.0f, 0.0f, 0.0f);
    for (uint k = 0u; k < IBL_SUN_POINTS; ++k) {
        float rho = radius * sqrt((IBL_FLOAT(k) + 0.5f) * (1.0f / IBL_FLOAT(IBL_SUN_POINTS)));
        vec3 L = v3normalize(v3add(D, v3add(v3scale(frame.t, rho * c), v3scale(frame.b, rho * s))));
        float cNext = c * -0.73736888f - s * 0.67549029f; // cos, sin of 2 pi (2 - golden ratio)
        s = c * 0.67549029f + s * -0.73736888f;
        c = cNext;
        vec3 H = v3safeNormalize(v3add(V, L), N);
        float NoL = saturate(v3dot(N, L)), NoH = saturate(v3dot(N, H)), LoH = saturate(v3dot(L, H));
        float dv = D_GGXFromCross(v3cross(N, H), NoH, alphaD) * V_SmithGGXCorrelated(NoVc, NoL, alphaV) * NoL;
        sum = v3madd(fresnelSchlickRgb(f0, f90, LoH), dv, sum);
    }
    return v3scale(sum, 1.0f / IBL_FLOAT(IBL_SUN_POINTS));
}

// The sun's specular per unit E_perp (IBL_RT_SUN_QUADRATURE). A lobe much narrower than the quadrature's
// point spacing would be sampled by a point or two (the highlight of a near-mirror jumps between points):
// there the normalized representative point is exact in the limit (a mirror facing the disk returns F
// times its radiance). Representative point below alpha = spacing / 4, quadrature above spacing, a linear
// blend between (r = 0 and 0.1 on disks of 0.27 and 1.6 degrees: tests/test_runtime_accuracy.cpp).
IBL_FN vec3 sunSpecularDisk(SunDisk sun, vec3 D, vec3 N, vec3 V, vec3 R, float NoVc, float NoD, float alpha,
                            vec3 f0, float f90) {
    float spacing = tan(sun.angularRadius) * sqrt(IBL_PI / IBL_FLOAT(IBL_SUN_POINTS));
    float t = saturate((alpha / fmax(spacing, 1e-12f) - 0.25f) * (1.0f / 0.75f));
    vec3 result = v3(0.0f, 0.0f, 0.0f);
    if (t < 1.0f)
        result =
            v3scale(sunSpecularRepresentativePoint(sun, N, V, R, NoVc, alpha, f0, f90, 1u), (1.0f - t) * NoD);
    if (t > 0.0f) result = v3madd(sunSpecularQuadrature(sun, D, N, V, NoVc, alpha, f0, f90), t, result);
    return result;
}

// ---------------------------------------------------------------------------------------------------
// Probes

IBL_STRUCT(ProbeSample) {
    vec3 radiance;
    float alpha;
};

// Below this visibility a texel counts as fully transparent: the un-premultiplication divides by it.
#define IBL_MIN_VISIBILITY 1e-6f

// Appendix F for one local probe: parallax-corrected, distance-based-rough LD and the probe's alpha.
// dominantR is unit. As in Listings F.1/F.2 the lookup direction is lerp(localR, dominantR, r) with localR
// the unnormalized capture-to-intersection vector (metres): the pull toward the uncorrected direction is
// r / (r + (1 - r) |localR|), so it depends on the scene's scale, as in the listings (normalizing localR
// first moved reflections near walls by up to a wall pattern's period at r = 0.2-0.3 in our glossy-floor
// test). The distance-based roughness chooses the LD level only: the DFG term and the energy compensation
// keep the material's roughness (the BRDF's albedo does not change with the footprint).
// alpha = influence weight x visibility, the visibility read like the LD (same direction, same level):
// the fade scales how much of the lobe the probe covers wherever it covers it, the texel visibility says
// where it covers it (a sky texel is 0 at any weight). radiance is the un-premultiplied colour LD / v, so
// that 4.9.5's rgb += radiance a adds LD w for the first probe and LD / v of the lobe's still uncovered
// part a for the next ones. Without visibility: alpha = weight and the LD as it is (the same operations as
// before visibility existed, so such probes give the same bits).
IBL_FN ProbeSample localProbeSpecular(LocalProbe probe, IBL_FLOAT_BUFFER localLd, vec3 position,
                                      vec3 dominantR, float perceptualRoughness, uint flags) {
    ProbeSample s;
    s.radiance = v3(0.0f, 0.0f, 0.0f);
    s.alpha = 0.0f;
    float weight =
        volumeIsValid(probe.proxy) ? influenceWeight(probe.influence, probe.fadeDistance, position) : 0.0f;
    ParallaxHit h = parallaxCorrect(probe.proxy, probe.captureOffset, position, dominantR);
    if (weight > 0.0f && h.hit) {
        float localRoughness =
            (flags & IBL_RT_DISTANCE_ROUGHNESS) != 0u
                ? computeDistanceBaseRoughness(h.distanceToHit, h.distanceFromCapture, perceptualRoughness)
                : perceptualRoughness;
        vec3 localR = v3scale(h.direction, h.distanceFromCapture);
        vec3 dir = v3safeNormalize(v3lerp(localR, dominantR, perceptualRoughness), dominantR);
        s.radiance = sampleLd(localLd, probe.ld, dir, localRoughness);
        s.alpha = weight;
        if (probe.hasVisibility != 0u) {
            float visibility =
                saturate(cubeSampleLodScalar(localLd + probe.visibilityOffset, probe.ld.shape, dir,
                                             ldLodForRoughness(probe.ld, localRoughness)));
            bool visible = visibility >= IBL_MIN_VISIBILITY;
            s.radiance = visible ? v3scale(s.radiance, 1.0f / visibility) : v3(0.0f, 0.0f, 0.0f);
            s.alpha = visible ? weight * visibility : 0.0f;
        }
    }
    return s;
}

// Frostbite 4.9.5 medium and large range: local probes in order (smallest influence first) while alpha < 1,
// each adding a = saturate(probe.alpha - alpha) of itself; the distant probe then gets the remaining
// 1 - alpha (composeSpecularLd). As the text says, overlapping probes are taken to cover the same part of the
// lobe (ten probes of alpha 0.1 give 0.1, not 1) and the result depends on the order.
IBL_FN ProbeSample composeLocalSpecularLd(RuntimeParams p,
                                          IBL_ARRAY_PARAM(LocalProbe, probes, IBL_MAX_LOCAL_PROBES),
                                          IBL_FLOAT_BUFFER localLd, vec3 position, vec3 dominantR,
                                          float perceptualRoughness) {
    ProbeSample result;
    result.radiance = v3(0.0f, 0.0f, 0.0f);
    result.alpha = 0.0f;
    for (uint i = 0u; i < p.localProbeCount && result.alpha < 1.0f; ++i) {
        ProbeSample s =
            localProbeSpecular(probes[i], localLd, position, dominantR, perceptualRoughness, p.flags);
        float a = saturate(s.alpha - result.alpha);
        result.radiance = v3madd(s.radiance, a, result.radiance);
        result.alpha = saturate(a + result.alpha);
    }
    return result;
}

// The taps were fitted for a chain of 256-px faces (tools/specular_taps); a chain of fewer levels holds their
// narrower lobes on coarser faces (its level at r = 0.16 has 8-px faces at 32 px): there the single read (a
// 32-px sky with its one-texel sun extracted read 5.5% mean column error with the taps,
// SunInProbe.WarnsWithTheErrorItCausesAndTheFix, where it needs under half the 8.8% with the sun kept).
#define IBL_SPECULAR_TAP_MIN_LEVELS 7u
IBL_FN bool distantSpecularTaps(RuntimeParams p) {
    return (p.flags & IBL_RT_SPECULAR_TAPS) != 0u &&
           p.distant.shape.levelCount >= IBL_SPECULAR_TAP_MIN_LEVELS;
}

// The distant probe's LD for the view's lobe: with distantSpecularTaps the weighted taps of specular_taps.h
// (directions normalize(lerp(N, R, t)), R the unit mirror direction), else one read at dominantR. Local
// probes keep the single read at dominantR (parallax-corrected): their proxies bend each direction
// differently, and the taps were fitted for a distant chain.
IBL_FN vec3 distantSpecularLd(RuntimeParams p, IBL_FLOAT_BUFFER distantLd, vec3 N, vec3 R, vec3 dominantR,
                              float NoV, float perceptualRoughness) {
    if (!distantSpecularTaps(p))
        return sampleLdWithLayers(distantLd, p.distant, p.distantRoughLayers, dominantR, perceptualRoughness);
    vec3 sum = v3(0.0f, 0.0f, 0.0f);
    for (uint k = 0u; k < IBL_SPECULAR_TAP_COUNT; ++k) {
        SpecularTap tap = specularTap(NoV, perceptualRoughness, k);
        vec3 d = v3safeNormalize(v3lerp(N, R, tap.lerpFactor), N);
        sum =
            v3madd(sampleLdWithLayers(distantLd, p.distant, p.distantRoughLayers, d, tap.perceptualRoughness),
                   tap.weight, sum);
    }
    return sum;
}

// The local probes, then the distant probe as distantSpecularLd reads it with the remaining 1 - alpha.
IBL_FN ProbeSample composeSpecularLd(RuntimeParams p, IBL_FLOAT_BUFFER distantLd,
                                     IBL_ARRAY_PARAM(LocalProbe, probes, IBL_MAX_LOCAL_PROBES),
                                     IBL_FLOAT_BUFFER localLd, vec3 position, vec3 N, vec3 R, vec3 dominantR,
                                     float NoV, float perceptualRoughness) {
    ProbeSample result = composeLocalSpecularLd(p, probes, localLd, position, dominantR, perceptualRoughness);
    if (result.alpha < 1.0f)
        result.radiance = v3madd(distantSpecularLd(p, distantLd, N, R, dominantR, NoV, perceptualRoughness),
                                 1.0f - result.alpha, result.radiance);
    return result;
}

// The share of the distant lookup at perceptual roughness r that level 0 gives: its trilinear weight 1 - lod,
// times the chain's share where rough layers (baked without the sun) take the rest.
IBL_FN float distantLevel0Share(RuntimeParams p, float perceptualRoughness) {
    float level0 = 1.0f - saturate(ldLodForRoughness(p.distant, perceptualRoughness));
    return p.distantRoughLayers.layerCount != 0u ? (1.0f - roughLayerWeight(perceptualRoughness)) * level0
                                                 : level0;
}

// Level 0's share of the distant specular as distantSpecularLd reads it.
IBL_FN float distantSpecularLevel0Share(RuntimeParams p, float NoV, float perceptualRoughness) {
    if (!distantSpecularTaps(p)) return distantLevel0Share(p, perceptualRoughness);
    float share = 0.0f;
    for (uint k = 0u; k < IBL_SPECULAR_TAP_COUNT; ++k) {
        SpecularTap tap = specularTap(NoV, perceptualRoughness, k);
        share += tap.weight * distantLevel0Share(p, tap.perceptualRoughness);
    }
    return share;
}

// ---------------------------------------------------------------------------------------------------
// The shading of one point

IBL_FN ShadeResult shadePoint(ShadingPoint sp, RuntimeParams p, IBL_FLOAT_BUFFER distantLd,
                              IBL_FLOAT_BUFFER dfgLut,
                              IBL_ARRAY_PARAM(LocalProbe, probes, IBL_MAX_LOCAL_PROBES),
                              IBL_FLOAT_BUFFER localLd) {
    uint flags = p.flags;
    vec3 N = v3safeNormalize(sp.normal, v3(0.0f, 1.0f, 0.0f));
    vec3 V = v3safeNormalize(sp.view, N);
    float NoVsigned = v3dot(N, V);
    float NoV = saturate(NoVsigned);
    float perceptualRoughness = saturate(sp.perceptualRoughness);
    float alpha = perceptualRoughness * perceptualRoughness;
    float metallic = saturate(sp.metallic);
    float ao = saturate(sp.ao);

    // Filament 4.8.3: diffuse colour and f0 from base colour and metallic; f90 = 1 or from f0 (5.6.2).
    vec3 diffuseColor = v3scale(sp.baseColor, 1.0f - metallic);
    float dielectric = p.dielectricF0 * (1.0f - metallic);
    vec3 f0 = v3madd(sp.baseColor, metallic, v3(dielectric, dielectric, dielectric));
    float f90 = (flags & IBL_RT_F90_FROM_F0) != 0u ? saturate(50.0f * 0.33f * (f0.x + f0.y + f0.z)) : 1.0f;

    vec3 dfg = dfgLookup(dfgLut, p.dfgSize, NoV, perceptualRoughness);
    float r = fmax(dfg.x + dfg.y, 1e-4f);
    vec3 energy = v3(1.0f, 1.0f, 1.0f);
    if ((flags & IBL_RT_ENERGY_COMPENSATION) != 0u)
        energy = v3(1.0f + f0.x * (1.0f / r - 1.0f), 1.0f + f0.y * (1.0f / r - 1.0f),
                    1.0f + f0.z * (1.0f / r - 1.0f));
    vec3 specularColor =
        v3(f0.x * dfg.x + f90 * dfg.y, f0.y * dfg.x + f90 * dfg.y, f0.z * dfg.x + f90 * dfg.y);

    // Mirror direction reflect(-V, N), then the dominant direction (halfway to the lobe's mean).
    vec3 R = v3sub(v3scale(N, 2.0f * NoVsigned), V);
    vec3 dominantR = (flags & IBL_RT_SPECULAR_DOMINANT) != 0u
                         ? specularDominantDirection(N, R, NoV, perceptualRoughness)
                         : v3safeNormalize(R, N);

    ShadeResult result;
    result.diffuse = v3(0.0f, 0.0f, 0.0f);
    result.specular = v3(0.0f, 0.0f, 0.0f);
    result.localAlpha = 0.0f;

    if ((flags & IBL_RT_SPECULAR) != 0u) {
        ProbeSample ld = composeSpecularLd(p, distantLd, probes, localLd, sp.position, N,
                                           v3safeNormalize(R, N), dominantR, NoV, perceptualRoughness);
        float occlusion =
            (flags & IBL_RT_SPECULAR_OCCLUSION) != 0u ? computeSpecOcclusion(NoV, ao, alpha) : 1.0f;
        if ((flags & IBL_RT_HORIZON_OCCLUSION) != 0u) occlusion *= horizonOcclusion(dominantR, N);
        result.specular =
            v3(ld.radiance.x * specularColor.x * energy.x, ld.radiance.y * specularColor.y * energy.y,
               ld.radiance.z * specularColor.z * energy.z);
        result.specular = v3scale(result.specular, occlusion);
        result.localAlpha = ld.alpha;
    }

    if ((flags & IBL_RT_DIFFUSE) != 0u) {
        vec3 nd = (flags & IBL_RT_DIFFUSE_DOMINANT) != 0u
                      ? v3safeNormalize(getDiffuseDominantDir(N, V, NoV, alpha), N)
                      : N;
        vec3 e = (flags & IBL_RT_IRRADIANCE_CUBE) != 0u
                     ? cubeSampleLevel(distantLd + p.irradiance.dataOffset, p.irradiance.shape, 0u,
                                       cubeCoordFromDirection(nd))
                     : irradianceSH(p.sh, nd);
        float scale = ((flags & (IBL_RT_SH_OVER_PI | IBL_RT_IRRADIANCE_CUBE)) != 0u ? 1.0f : IBL_INV_PI) *
                      ao * ((flags & IBL_RT_DISNEY_DIFFUSE) != 0u ? dfg.z : 1.0f);
        result.diffuse =
            v3(diffuseColor.x * fmax(e.x, 0.0f) * scale, diffuseColor.y * fmax(e.y, 0.0f) * scale,
               diffuseColor.z * fmax(e.z, 0.0f) * scale);
    }

    if ((flags & IBL_RT_SUN) != 0u) {
        // Listing 6: E = E_perp <N.D>; diffuse as a punctual light in D, specular toward the disk point L.
        vec3 D = v3safeNormalize(p.sun.direction, v3(0.0f, 1.0f, 0.0f));
        float NoD = saturate(v3dot(N, D));
        vec3 E = v3scale(p.sun.color, p.sun.illuminance * NoD);
        float NoVc = fmax(NoV, 1e-4f);
        float fd = 1.0f;
        if ((flags & IBL_RT_DISNEY_DIFFUSE) != 0u) {
            float LoH = sqrt(saturate(0.5f + 0.5f * v3dot(V, D)));
            fd = Fr_DisneyDiffuse(NoVc, NoD, LoH, perceptualRoughness);
        }
        if ((flags & IBL_RT_DIFFUSE) != 0u)
            result.diffuse = v3madd(v3(diffuseColor.x * E.x, diffuseColor.y * E.y, diffuseColor.z * E.z),
                                    fd * IBL_INV_PI, result.diffuse);

        if ((flags & IBL_RT_SPECULAR) != 0u) {
            vec3 spec = (flags & IBL_RT_SUN_QUADRATURE) != 0u
                            ? sunSpecularDisk(p.sun, D, N, V, R, NoVc, NoD, alpha, f0, f90)
                            : v3scale(sunSpecularRepresentativePoint(p.sun, N, V, R, NoVc, alpha, f0, f90,
                                                                     flags & IBL_RT_SUN_NORMALIZATION),
                                      NoD);
            float sunWeight = p.sun.illuminance;
            // The disk gets what level 0 does not (level 0 holds the sun's pixels).
            if ((flags & IBL_RT_SUN_IN_LEVEL0) != 0u)
                sunWeight *= 1.0f - distantSpecularLevel0Share(p, NoV, perceptualRoughness);
            result.specular = v3add(result.specular, v3(spec.x * energy.x * p.sun.color.x * sunWeight,
                                                        spec.y * energy.y * p.sun.color.y * sunWeight,
                                                        spec.z * energy.z * p.sun.color.z * sunWeight));
        }
    }
    return result;
}

IBL_END_NAMESPACE

#endif
