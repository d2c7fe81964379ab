// Runtime textured rectangle lights: a rectangle AreaLight (area_lights.h) whose emission is a light card
// (light_card.h), Drobot 1.3.5 eq. 1.24 and 1.28: the uniform light's diffuse and specular (the form factor
// and the representative point of area_lights.h, for the light's mean radiance) times the card's
// normalized pre-integrated emission at the most important points:
//   diffuse   p_d where the visible part's vector-irradiance direction (the direction area_lights.h lights
//             the diffuse with) meets the light, read from the diffuse layers at r = the point's height above
//             the light's plane: the card's layer holds the light seen from p_d + r n_l (eq. 1.23's lookup),
//             whose kernel is then as wide as the point's own (measured: 3.3% mean error at 1 light size,
//             3.8% with Drobot's r = |p - p_d|, which is wider for oblique points), eq. 1.24
//   specular  p_sc, the centre of the specular cone's overlap with the light (area_lights.h, eq. 1.19-1.23),
//             read from the specular chain at the footprint radius |p_sc - p| tan(alpha) (eq. 1.26), eq. 1.28
// The card holds the emission normalized to mean luminance 1; light.color x light.luminance scale it as for a
// uniform light of the same luminous power (Frostbite Table 12).
#ifndef IBL_TEXTURED_LIGHT_H
#define IBL_TEXTURED_LIGHT_H

#include "area_lights.h"
#include "light_card.h"

IBL_BEGIN_NAMESPACE

// Bilinear read of (level, layer) at light-space (u, v) in [0, 1]^2, clamped to the edge texels.
IBL_FN vec3 lightCardBilinear(IBL_FLOAT_BUFFER data, LightCardLayout card, uint level, uint layer, float u,
                              float v) {
    uint w = lightCardLevelSize(card.width, level), h = lightCardLevelSize(card.height, level);
    uint base = lightCardOffset(card, level, layer);
    float x = clamp(u * IBL_FLOAT(w) - 0.5f, 0.0f, IBL_FLOAT(w - 1u));
    float y = clamp(v * IBL_FLOAT(h) - 0.5f, 0.0f, IBL_FLOAT(h - 1u));
    uint x0 = IBL_UINT(x), y0 = IBL_UINT(y);
    uint x1 = min(x0 + 1u, w - 1u), y1 = min(y0 + 1u, h - 1u);
    float fx = x - IBL_FLOAT(x0), fy = y - IBL_FLOAT(y0);
    uint i00 = base + 4u * (y0 * w + x0), i10 = base + 4u * (y0 * w + x1);
    uint i01 = base + 4u * (y1 * w + x0), i11 = base + 4u * (y1 * w + x1);
    return weightedRgb4(data, i00, i10, i01, i11, (1.0f - fx) * (1.0f - fy), fx * (1.0f - fy),
                        (1.0f - fx) * fy, fx * fy);
}

// The specular card at footprint radius rho (card units): trilinear between the two levels around it.
IBL_FN vec3 lightCardSpecular(IBL_FLOAT_BUFFER data, LightCardLayout card, float u, float v, float rho) {
    float level = lightCardLevelForFootprint(card, rho);
    uint m0 = IBL_UINT(level);
    uint m1 = min(m0 + 1u, card.levelCount - 1u);
    float f = level - IBL_FLOAT(m0);
    vec3 a = lightCardBilinear(data, card, m0, 0u, u, v), b = lightCardBilinear(data, card, m1, 0u, u, v);
    return v3add(v3scale(a, 1.0f - f), v3scale(b, f));
}

// The diffuse card at distance r (card units): linear between the two layers around it.
IBL_FN vec3 lightCardDiffuse(IBL_FLOAT_BUFFER data, LightCardLayout card, float u, float v, float r) {
    float layer = lightCardLayerForDistance(card, r);
    uint k0 = IBL_UINT(layer);
    uint k1 = min(k0 + 1u, card.diffuseLayers - 1u);
    float f = layer - IBL_FLOAT(k0);
    vec3 a = lightCardBilinear(data, card, 0u, 1u + k0, u, v),
         b = lightCardBilinear(data, card, 0u, 1u + k1, u, v);
    return v3add(v3scale(a, 1.0f - f), v3scale(b, f));
}

// Light-space (u, v) of a point of the light's plane at (px, py) from its centre (tangent, bitangent).
IBL_FN float2 lightCardUv(LightPlane plane, float px, float py) {
    return make_float2(saturate(0.5f + 0.5f * px / plane.halfWidth),
                       saturate(0.5f - 0.5f * py / plane.halfHeight));
}

// A textured rectangle light (light.shape IBL_AREA_RECTANGLE; light.color and light.luminance as for the
// uniform light) on one surface, flags as areaLightShade. Zero where the uniform light is zero.
IBL_FN AreaLightResult texturedLightShade(AreaLight light, LightCardLayout card, IBL_FLOAT_BUFFER data,
                                          AreaSurface s, uint flags) {
    AreaLightGeometry g = areaLightGeometry(light, s);
    AreaLightResult r = areaLightShadeGeometry(g, v3scale(light.color, light.luminance), s, flags);
    if (g.illuminance <= 0.0f) return r;
    LightPlane plane = g.plane;
    float sqrtArea = 2.0f * sqrt(plane.halfWidth * plane.halfHeight);
    if ((flags & IBL_RT_DIFFUSE) != 0u) {
        // p_d: the diffuse direction's hit on the light's plane (inside the light: the visible part's
        // centroid direction; clamped for the rounding at its edges); the lookup's distance is the point's
        // height.
        vec3 toCenter = v3sub(plane.center, s.P);
        float height = -v3dot(toCenter, plane.normal);
        float along = -v3dot(g.direction, plane.normal);
        vec3 hit = along > 1e-6f ? v3scale(g.direction, height / along) : toCenter;
        vec3 fromCenter = v3sub(hit, toCenter);
        float px = clamp(v3dot(fromCenter, plane.tangent), -plane.halfWidth, plane.halfWidth);
        float py = clamp(v3dot(fromCenter, plane.bitangent), -plane.halfHeight, plane.halfHeight);
        float2 uv = lightCardUv(plane, px, py);
        vec3 c = lightCardDiffuse(data, card, uv.x, uv.y, height / sqrtArea);
        r.diffuse = v3(r.diffuse.x * c.x, r.diffuse.y * c.y, r.diffuse.z * c.z);
    }
    if ((flags & IBL_RT_SPECULAR) != 0u) {
        SpecularPoint sc = areaSpecularPoint(plane, s);
        float2 uv = lightCardUv(plane, sc.px, sc.py);
        float distance = sqrt(v3dot(sc.toPoint, sc.toPoint));
        float rho = lightCardFootprint(s.alpha, distance, sqrtArea * sqrtArea);
        vec3 c = lightCardSpecular(data, card, uv.x, uv.y, rho);
        r.specular = v3(r.specular.x * c.x, r.specular.y * c.y, r.specular.z * c.z);
    }
    return r;
}

IBL_END_NAMESPACE

#endif
