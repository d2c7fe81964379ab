// Local light probe geometry (Frostbite 2014, 4.9.3 "Re-projection" and Appendix F, Listings F.1 and F.2):
// sphere and oriented-box volumes, the far intersection of the reflected ray with the proxy, the parallax-
// corrected lookup direction from the capture point, distance-based roughness (Listing 25), and the
// influence weight with its fade distance. Portable (OpenCL C and C++, see portable.h).
//
// Conventions of this module:
// - A volume has a centre and three orthonormal world axes; a point's local coordinates are its offsets
//   along them (F.2's "invTransform ... without scaling"). A box has half extents along the axes, a sphere
//   its radius in extent.x (its axes only orient the capture offset).
// - The capture point is proxy.center + captureOffset given along the proxy's axes (F.2's localOffset).
// - The probe's cube is in world orientation (the docs/conventions.md frame, not the box's frame): the
// corrected
//   direction is turned back to world axes before the lookup.
// - A volume with a radius or half extent that is not > 0 (zero size, negative, NaN) is invalid: a probe
//   with an invalid proxy or influence volume has weight 0 everywhere, and nothing is divided by its size.
// Every function returns finite values for finite inputs: rays parallel to box faces, points on or outside
// the volumes, points at the capture point and zero-length directions included.
#ifndef IBL_PARALLAX_H
#define IBL_PARALLAX_H

#include "portable.h"

IBL_BEGIN_NAMESPACE

#define IBL_VOLUME_SPHERE 0u
#define IBL_VOLUME_BOX 1u
// Stands in for infinity in the slab test (finite, so 0 * it stays 0 and selects stay NaN-free).
#define IBL_PARALLAX_FAR 1e30f

IBL_STRUCT(ProbeVolume) {
    uint32_t shape; // IBL_VOLUME_SPHERE or IBL_VOLUME_BOX
    vec3 center;
    vec3 axisX; // orthonormal world axes of the local frame
    vec3 axisY;
    vec3 axisZ;
    vec3 extent; // box: half extents along the axes; sphere: radius in x (y, z unused)
};

IBL_FN float v3length(vec3 a) {
    return sqrt(v3dot(a, a));
}

// a / |a|, or `fallback` when |a| is zero or too small to divide by.
IBL_FN vec3 v3safeNormalize(vec3 a, vec3 fallback) {
    float l2 = v3dot(a, a);
    return l2 > 1e-30f ? v3scale(a, 1.0f / sqrt(l2)) : fallback;
}

// HLSL lerp, a + t (b - a), per component (GLM's mix rounds differently; this is what the listings use).
IBL_FN float lerpf(float a, float b, float t) {
    return a + t * (b - a);
}
IBL_FN vec3 v3lerp(vec3 a, vec3 b, float t) {
    return v3(lerpf(a.x, b.x, t), lerpf(a.y, b.y, t), lerpf(a.z, b.z, t));
}

// smoothstep(0, 1, x) for x in [0, 1]: Listings F.1/F.2's smoothstep(alpha).
IBL_FN float smoothstep01(float x) {
    return x * x * (3.0f - 2.0f * x);
}

IBL_FN vec3 volumeDirectionToLocal(ProbeVolume v, vec3 d) {
    return v3(v3dot(d, v.axisX), v3dot(d, v.axisY), v3dot(d, v.axisZ));
}
IBL_FN vec3 volumePointToLocal(ProbeVolume v, vec3 p) {
    return volumeDirectionToLocal(v, v3sub(p, v.center));
}
IBL_FN vec3 volumeDirectionToWorld(ProbeVolume v, vec3 d) {
    return v3madd(v.axisX, d.x, v3madd(v.axisY, d.y, v3scale(v.axisZ, d.z)));
}

// Radius / half extents all > 0 (false for NaN).
IBL_FN bool volumeIsValid(ProbeVolume v) {
    bool sphereOk = v.extent.x > 0.0f;
    bool boxOk = v.extent.x > 0.0f && v.extent.y > 0.0f && v.extent.z > 0.0f;
    return v.shape == IBL_VOLUME_SPHERE ? sphereOk : (v.shape == IBL_VOLUME_BOX ? boxOk : false);
}

// Parameter interval [x, y] of the ray p + t d (local coordinates, d need not be unit) inside the volume;
// x > y when the line misses it. F.1's sphereRayIntersect and F.2's boxRayIntersect (slab test).
IBL_FN float2 sphereRayIntersect(vec3 p, vec3 d, float radius) {
    float a = v3dot(d, d);
    float inva = a > 0.0f ? 1.0f / a : 0.0f;
    float b = v3dot(p, d) * inva;
    float c = (v3dot(p, p) - radius * radius) * inva;
    float disc = b * b - c;
    float s = sqrt(fmax(disc, 0.0f));
    bool miss = disc < 0.0f || a <= 0.0f;
    return miss ? make_float2(IBL_PARALLAX_FAR, -IBL_PARALLAX_FAR) : make_float2(-b - s, -b + s);
}

// One slab |p + t d| <= e: its interval, or everything / nothing for a ray parallel to it.
IBL_FN float2 slabInterval(float p, float d, float e) {
    bool parallel = fabs(d) < 1e-20f;
    float inv = 1.0f / (parallel ? 1.0f : d);
    float ta = (-e - p) * inv, tb = (e - p) * inv;
    bool inside = fabs(p) <= e;
    float t0 = parallel ? (inside ? -IBL_PARALLAX_FAR : IBL_PARALLAX_FAR) : fmin(ta, tb);
    float t1 = parallel ? (inside ? IBL_PARALLAX_FAR : -IBL_PARALLAX_FAR) : fmax(ta, tb);
    return make_float2(t0, t1);
}

IBL_FN float2 boxRayIntersect(vec3 p, vec3 d, vec3 halfExtent) {
    float2 sx = slabInterval(p.x, d.x, halfExtent.x);
    float2 sy = slabInterval(p.y, d.y, halfExtent.y);
    float2 sz = slabInterval(p.z, d.z, halfExtent.z);
    return make_float2(fmax(sx.x, fmax(sy.x, sz.x)), fmin(sx.y, fmin(sy.y, sz.y)));
}

IBL_STRUCT(ParallaxHit) {
    bool hit;                  // the ray leaves the proxy ahead of the receiver (far intersection t >= 0)
    float distanceToHit;       // receiver -> intersection (t for a unit direction)
    float distanceFromCapture; // capture point -> intersection
    vec3 direction;            // capture point -> intersection, world axes, unit (the ray itself when
                               // the intersection is the capture point)
};

// Re-projection of a unit world direction `dir` from the receiver `position` onto the proxy, as in
// Listings F.1 (sphere) and F.2 (box): only the far intersection counts, so a receiver inside the proxy
// always hits it. The capture point is proxy.center + captureOffset (offset along the proxy's axes).
IBL_FN ParallaxHit parallaxCorrect(ProbeVolume proxy, vec3 captureOffset, vec3 position, vec3 dir) {
    vec3 localPos = volumePointToLocal(proxy, position);
    vec3 localDir = volumeDirectionToLocal(proxy, dir);
    float2 t = proxy.shape == IBL_VOLUME_BOX ? boxRayIntersect(localPos, localDir, proxy.extent)
                                             : sphereRayIntersect(localPos, localDir, proxy.extent.x);
    ParallaxHit h;
    h.hit = volumeIsValid(proxy) && t.y >= t.x && t.y >= 0.0f;
    float tFar = h.hit ? t.y : 0.0f;
    // Intersection relative to the capture point, in the proxy's frame, then in world axes.
    vec3 localR = v3sub(v3madd(localDir, tFar, localPos), captureOffset);
    h.distanceToHit = tFar;
    h.distanceFromCapture = v3length(localR);
    h.direction = v3safeNormalize(volumeDirectionToWorld(proxy, localR), dir);
    return h;
}

// Listing 25 (Frostbite 4.9.3), on the perceptual ("linear") roughness. For distances whose ratio is a
// normal float this is the listing bit for bit: clamp(d1 / d2 * r, 0, r), then lerp(that, r, r). The ratio
// is bounded (d2 -> 0 gives the listing's limit r instead of 0 * inf = NaN for r = 0).
IBL_FN float computeDistanceBaseRoughness(float distIntersectionToShadedPoint,
                                          float distIntersectionToProbeCenter, float linearRoughness) {
    float ratio = fmin(distIntersectionToShadedPoint / fmax(distIntersectionToProbeCenter, 1e-30f), 1e30f);
    // To avoid artifacts we clamp to the original linearRoughness which introduces an acceptable bias and
    // allows conservation of mirror reflection behavior for a smooth surface.
    float newLinearRoughness = clamp(ratio * linearRoughness, 0.0f, linearRoughness);
    return lerpf(newLinearRoughness, linearRoughness, linearRoughness);
}

// F.2's distanceBoxPoint: distance from p to the box [boxMin, boxMax] (0 inside).
IBL_FN float distanceBoxPoint(vec3 boxMin, vec3 boxMax, vec3 p) {
    vec3 d =
        v3(fmax(fmax(boxMin.x - p.x, 0.0f), p.x - boxMax.x), fmax(fmax(boxMin.y - p.y, 0.0f), p.y - boxMax.y),
           fmax(fmax(boxMin.z - p.z, 0.0f), p.z - boxMax.z));
    return v3length(d);
}

// Influence weight in [0, 1] with a soft transition of width fadeDistance inside the boundary (F.1 for a
// sphere, F.2 for a box, both through smoothstep). Exactly 0 on and outside the boundary (also for a fade
// distance of 0, where the listings' max(fade, 0.0001) would leave a 0.1 mm band outside a box), and 0
// for an invalid volume.
IBL_FN float influenceWeight(ProbeVolume v, float fadeDistance, vec3 position) {
    vec3 q = volumePointToLocal(v, position);
    float fade = fmax(fadeDistance, 0.0f);
    float fadeSafe = fmax(fade, 0.0001f);
    float sphereAlpha = saturate((v.extent.x - v3length(q)) / fadeSafe);
    vec3 fade3 = v3(fade, fade, fade);
    float boxDistance = distanceBoxPoint(v3sub(fade3, v.extent), v3sub(v.extent, fade3), q);
    bool insideBox = fabs(q.x) < v.extent.x && fabs(q.y) < v.extent.y && fabs(q.z) < v.extent.z;
    float boxAlpha = insideBox ? 1.0f - saturate(boxDistance / fadeSafe) : 0.0f;
    float alpha = v.shape == IBL_VOLUME_BOX ? boxAlpha : sphereAlpha;
    return volumeIsValid(v) ? smoothstep01(alpha) : 0.0f;
}

IBL_END_NAMESPACE

#endif
