// Light cards: textured rectangle lights pre-integrated as Drobot, "Physically Based Area Lights" (GPU Pro
// 5), 1.3.5 (eq. 1.23-1.28, Figures 1.25-1.26) and 1.4.1 describe. One source for the baker (the card's bake,
// kernels/light_card_bake.h), the runtime (kernels/textured_light.h) and the files' metadata.
//
// The card. The light is a rectangle; its texture covers it with u along the light's tangent (u = 0 at the
// -tangent edge) and v against its bitangent (v = 0, the first scanline, at the +bitangent edge), so the
// image reads unmirrored seen from the emitting side with the tangent to the right. Lengths on the card
// are in units of sqrt(light area) (the card is baked for the light's aspect width / height, `aspect`). The
// texels are the emission normalized to mean luminance 1 over the light (Drobot 1.3.5: "light intensity I
// is constant over the light and L_i returns a normalized, wavelength dependent value").
// One KTX2 2D array texture: `levelCount` levels of `1 + diffuseLayers` layers.
//   layer 0, level m   the specular card (Figure 1.25, eq. 1.27): the texture pre-integrated over a footprint
//                      of radius rho_m (lightCardLevelFootprint); level 0 is the texture itself (a mirror)
//   layer 1 + k, level 0  the diffuse card (Figure 1.26, eq. 1.23's Diffuse_Lookup): the texture integrated
//                      as seen from normalized distance t_k = (k / (K - 1))^2 of r_max
//                      (lightCardLayerDistance); its deeper levels are plain 2x2 box reductions (no reader
//                      needs them)
//
// The pre-integration kernel. Both lookups are normalized integrals over the light: sum T w / sum w, so a
// constant card returns its constant and the runtime's uniform rectangle light (area_lights.h) supplies
// the absolute level (Drobot: "multiply those results by the pre-integrated, normalized full integral").
//   diffuse   the light seen from the point at distance r above p_d, as a receiver facing the light weighs
//             it: cos(theta_light) cos(theta_receiver) / d^2 = r^2 / (r^2 + x^2)^2 ~ 1 / (1 + x^2 / r^2)^2,
//             x the distance from p_d on the light.
//   specular  GGX (alpha) seen at normal incidence from distance t, in the light's plane: D(h) with
//             tan(theta_h) ~ x / (2 t), 1 / (1 + x^2 / (4 t^2 alpha^2))^2 (small-angle form). With the
//             footprint radius rho = t tan(alpha) of area_lights.h's cone (half-angle alpha, eq. 1.18
//             through g = 2 / alpha^2 - 2) this is 1 / (1 + x^2 / (2 rho)^2)^2: one parameter, rho, which
//             eq. 1.26's g' = f_BRDF(g, r) becomes. Drobot's kernel is Phong's (1.3.5: h orthogonal to the
//             view "effectively forces us to use Phong"); ours is GGX's radially symmetric lobe at normal
//             incidence, so oblique views stretch the true footprint by up to 1 / cos that the card ignores.
//   Both are w(x) = 1 / (1 + x^2 / beta^2)^2: beta = r for diffuse, beta = 2 rho for specular.
#ifndef IBL_LIGHT_CARD_H
#define IBL_LIGHT_CARD_H

#include "portable.h"

IBL_BEGIN_NAMESPACE

// Drobot 1.3.5: r_max > sqrt(dA / sigma), beyond which the diffuse integral no longer changes visibly. With
// sigma = 0.01 and dA = 1 (card units) r_max = 10 light sizes; at r_max the kernel w varies by 0.5% across
// the light (1 / (1 + (0.5 / 10)^2)^2).
#define IBL_CARD_SIGMA 0.01f
// The largest footprint the specular chain holds (its last level), in card units: there w varies by 6%
// across a square light, so larger footprints read the last level (the card's weighted mean).
#define IBL_CARD_MAX_FOOTPRINT 2.0f

// The mapping's parameters, as the file stores them (KTX2 keys iblbake.card*).
IBL_STRUCT(LightCardLayout) {
    uint32_t width, height; // level 0, texels (powers of two)
    uint32_t levelCount;    // floor(log2(max(width, height))) + 1: every level down to 1x1
    uint32_t diffuseLayers; // K >= 2: layers 1..K
    float aspect;           // the light's width / height the card was baked for
    float maxDistance;      // r_max, card units: sqrt(1 / IBL_CARD_SIGMA)
    uint32_t pad0, pad1;
};

IBL_FN float lightCardMaxDistance(void) {
    return sqrt(1.0f / IBL_CARD_SIGMA);
}

// The footprint radius level m holds, card units: 0 for level 0, rho_m = IBL_CARD_MAX_FOOTPRINT 2^(m - L + 1)
// for m >= 1 (a factor 2 per level, as the texel size; level 1's radius is 4 level-0 texels when L is the
// full chain of a square card).
IBL_FN float lightCardLevelFootprint(LightCardLayout card, uint level) {
    if (level == 0u) return 0.0f;
    float rho = IBL_CARD_MAX_FOOTPRINT;
    for (uint m = level + 1u; m < card.levelCount; ++m)
        rho *= 0.5f;
    return rho;
}

// The fractional level that holds footprint radius rho (card units): linear from level 0 (rho = 0) to level
// 1, log2 above, clamped to the last level.
IBL_FN float lightCardLevelForFootprint(LightCardLayout card, float rho) {
    float last = IBL_FLOAT(card.levelCount - 1u);
    if (card.levelCount <= 1u) return 0.0f;
    float rho1 = lightCardLevelFootprint(card, 1u);
    if (!(rho > rho1)) return saturate(fmax(rho, 0.0f) / rho1);
    return fmin(1.0f + log2(rho / rho1), last);
}

// Drobot eq. 1.26 for our GGX: the footprint radius (card units) of the specular cone of half-angle alpha
// (area_lights.h, eq. 1.18) at distance `distance` (m) from a light of area `area` (m^2).
IBL_FN float lightCardFootprint(float alpha, float distance, float area) {
    return distance * tan(fmin(alpha, 1.5f)) / sqrt(area);
}

// The normalized distance t of diffuse layer k (0-based among the K diffuse layers): (k / (K - 1))^2, so
// layers crowd near the light where the integral changes fastest; r = t r_max. Layer 0 is the texture.
IBL_FN float lightCardLayerDistance(LightCardLayout card, uint layer) {
    float t = IBL_FLOAT(layer) / IBL_FLOAT(card.diffuseLayers - 1u);
    return t * t * card.maxDistance;
}

// The fractional diffuse layer (0-based) for distance r (card units): Drobot's min(r / r_max, 1) (the text
// prints max, which would put every point nearer than r_max on the last layer), through the square root.
IBL_FN float lightCardLayerForDistance(LightCardLayout card, float r) {
    return sqrt(saturate(r / card.maxDistance)) * IBL_FLOAT(card.diffuseLayers - 1u);
}

// The pre-integration kernel w(x) = 1 / (1 + x^2 / beta^2)^2 for squared distance x^2 and 1 / beta^2.
IBL_FN float lightCardWeight(float distanceSqr, float invBetaSqr) {
    float q = 1.0f + distanceSqr * invBetaSqr;
    return 1.0f / (q * q);
}

// Level m's size along an axis of level-0 size n.
IBL_FN uint lightCardLevelSize(uint n, uint level) {
    return max(n >> level, 1u);
}

// The first float of (level, layer) in the card's data: levels from 0, each holding its 1 + K layers of
// 4-float RGBA texels, row by row (KTX2's order within a level: layer by layer).
IBL_FN uint lightCardOffset(LightCardLayout card, uint level, uint layer) {
    uint offset = 0u;
    uint layers = card.diffuseLayers + 1u;
    for (uint m = 0u; m < level; ++m)
        offset += 4u * layers * lightCardLevelSize(card.width, m) * lightCardLevelSize(card.height, m);
    return offset +
           4u * layer * lightCardLevelSize(card.width, level) * lightCardLevelSize(card.height, level);
}

IBL_END_NAMESPACE

#endif
