// Runtime area lights: sphere, disk and rectangle emitters of uniform luminance (Frostbite 2014 section 4.7,
// Drobot, "Physically Based Area Lights", GPU Pro 5, 1.3.3-1.3.4), for the standard material of probe.h
// (GGX, height-correlated Smith, Schlick; Lambert or renormalized Disney diffuse). One source for OpenCL C,
// C++ and GLSL (probe.h includes it, so it is part of probe.glsl).
//   units     the input is luminous power (lm), converted once to the luminance (nits, cd/m^2) the
//             evaluation works in by Frostbite Table 12 (eq. 33: L = phi / (A pi) for a Lambertian emitter;
//             a sphere emits from its whole surface, disks and rectangles from their front face only)
//   diffuse   illuminance E = integral of L <n.l> over the light, horizon included: the sphere by Listing
//             10's form factor (exact), disk and rectangle by Lambert's contour integral (Listing E.1) of the
//             light's outline clipped to the surface's horizon plane ([McG10], Appendix E), the disk as the
//             regular 16-gon of its area. That is exact where Frostbite's choices are not: Listing 10's disk
//             (the tilted-plane form factor times <n_l.-l>) was 26-48% low for a disk seen 57 degrees off its
//             axis at 1 light size (10% at 3), and Listing 12 samples the rectangle's cosine at 5 points.
//             Disney's term is applied for one direction (4.7.4, eq. 45): the clipped outline's vector-
//             irradiance direction (the centroid of the light's visible part; Frostbite takes the centre).
//   specular  a representative point (Drobot 1.3.4, eq. 1.19-1.20) with an energy normalization for GGX,
//             see areaSpecular below for where it follows Drobot and where it departs.
// The tube light is not here: Frostbite 4.7.2.6 builds it from a facing rectangle and a sphere at the
// closest point of the segment, both of which this header has.
#ifndef IBL_AREA_LIGHTS_H
#define IBL_AREA_LIGHTS_H

#include "brdf.h"
#include "parallax.h" // v3safeNormalize
#include "sampling.h"
#include "shading_point.h"

IBL_BEGIN_NAMESPACE

#define IBL_AREA_SPHERE 0u
#define IBL_AREA_DISK 1u
#define IBL_AREA_RECTANGLE 2u
// Outlines: a disk is a regular polygon of IBL_DISK_VERTICES vertices (and the disk's area).
#define IBL_POLYGON_MAX 16
#define IBL_DISK_VERTICES 16

// One area light (4-byte members only: the same layout in C++, OpenCL C and GLSL's std430).
IBL_STRUCT(AreaLight) {
    vec3 position;    // centre, m
    uint32_t shape;   // IBL_AREA_*
    vec3 normal;      // disk and rectangle: unit, the emitting side
    float halfWidth;  // sphere and disk: the radius; rectangle: half its extent along `tangent`, m
    vec3 tangent;     // rectangle: unit, perpendicular to `normal`
    float halfHeight; // rectangle: half its extent along cross(normal, tangent), m
    vec3 color;       // linear RGB, luminance 1
    float luminance;  // nits (cd/m^2) of the emitting surface
};

// Frostbite Table 12: luminance (nits) of a light of luminous power `lumens`.
IBL_FN float areaLightLuminanceFromPower(uint shape, float halfWidth, float halfHeight, float lumens) {
    float r2 = halfWidth * halfWidth;
    if (shape == IBL_AREA_SPHERE) return lumens / (4.0f * r2 * IBL_PI * IBL_PI);
    if (shape == IBL_AREA_DISK) return lumens / (r2 * IBL_PI * IBL_PI);
    return lumens / (4.0f * halfWidth * halfHeight * IBL_PI);
}

// Listing 10: the illuminance of a sphere or facing disk of unit luminance subtending sin^2(sigma), at the
// angle theta between the normal and the light's centre (cosTheta unclamped), horizon included.
IBL_FN float illuminanceSphereOrDisk(float cosTheta, float sinSigmaSqr) {
    float sinTheta = sqrt(fmax(1.0f - cosTheta * cosTheta, 0.0f));
    float illuminance = 0.0f;
    if (cosTheta * cosTheta > sinSigmaSqr) {
        illuminance = IBL_PI * sinSigmaSqr * saturate(cosTheta);
    } else {
        float x = sqrt(1.0f / sinSigmaSqr - 1.0f);
        float y = -x * (cosTheta / sinTheta);
        float sinThetaSqrtY = sinTheta * sqrt(fmax(1.0f - y * y, 0.0f));
        illuminance = (cosTheta * acos(clamp(y, -1.0f, 1.0f)) - x * sinThetaSqrtY) * sinSigmaSqr +
                      atan2(sinThetaSqrtY, x);
    }
    return fmax(illuminance, 0.0f);
}

// One edge of Lambert's contour integral (Listing E.1): theta * unit(a x b) for unit a, b, with theta =
// atan2(|a x b|, a.b), finite for the short and degenerate edges that clipping produces.
IBL_FN vec3 contourEdge(vec3 a, vec3 b) {
    vec3 c = v3cross(a, b);
    float s = sqrt(v3dot(c, c));
    float theta = atan2(s, v3dot(a, b));
    return v3scale(c, s > 1e-12f ? theta / s : 1.0f);
}

// The illuminance of a convex polygon light (a rectangle, or a disk as a regular polygon): vertices
// relative to the point, in order around the light. Sutherland-Hodgman clips the polygon to N's positive
// half-space (one vertex more at most), then Lambert's contour integral of the clipped polygon gives the
// vector irradiance S; E = S.N / 2 (Listing E.1's pi / (2 pi)). `direction` is S's direction: the
// solid-angle centroid of the light's part above the horizon, or `fallback`.
IBL_STRUCT(PolygonIrradiance) {
    float illuminance; // of unit luminance
    vec3 direction;
};
IBL_FN PolygonIrradiance polygonIrradiance(vec3 corners[IBL_POLYGON_MAX], int n, vec3 N, vec3 fallback) {
    vec3 poly[IBL_POLYGON_MAX + 1];
    int count = 0;
    vec3 vertexSum = v3(0.0f, 0.0f, 0.0f);
    for (int i = 0; i < n; ++i) {
        vec3 a = corners[i], b = corners[i + 1 < n ? i + 1 : 0];
        float ha = v3dot(a, N), hb = v3dot(b, N);
        vertexSum = v3add(vertexSum, a);
        if (ha >= 0.0f) {
            poly[count] = a;
            count += 1;
        }
        if ((ha >= 0.0f) != (hb >= 0.0f)) {
            poly[count] = v3add(a, v3scale(v3sub(b, a), ha / (ha - hb)));
            count += 1;
        }
    }
    vec3 sum = v3(0.0f, 0.0f, 0.0f);
    for (int i = 0; i < count; ++i) {
        int j = i + 1 < count ? i + 1 : 0;
        sum = v3add(sum, contourEdge(v3safeNormalize(poly[i], N), v3safeNormalize(poly[j], N)));
    }
    // The winding sets S's sign: S points from the point toward the light.
    if (v3dot(sum, vertexSum) < 0.0f) sum = v3scale(sum, -1.0f);
    PolygonIrradiance result;
    result.illuminance = count >= 3 ? fmax(0.5f * v3dot(sum, N), 0.0f) : 0.0f;
    result.direction = v3safeNormalize(sum, fallback);
    return result;
}

// Drobot eq. 1.22 and 1.23 on one axis: the centre of the overlap of the light [-h, h] and the cone's
// footprint [c - r, c + r], or the light's edge nearest the footprint when they do not overlap. (Eq. 1.22 is
// this for partial overlap; the midpoint also covers the footprint inside the light or around it.)
IBL_FN float overlapCentre(float c, float r, float h) {
    float lo = fmax(-h, c - r), hi = fmin(h, c + r);
    return lo <= hi ? 0.5f * (lo + hi) : clamp(c, -h, h);
}
// The fraction of the light's [-h, h] inside the footprint [c - r, c + r].
IBL_FN float overlapCoverage(float c, float r, float h) {
    return saturate((fmin(h, c + r) - fmax(-h, c - r)) / (2.0f * h));
}

// The surface a light falls on, in the terms of probe.h's shadePoint.
IBL_STRUCT(AreaSurface) {
    vec3 P, N, V;
    float NoV; // >= 1e-4
    float perceptualRoughness, alpha;
    vec3 diffuseColor, f0;
    float f90;
};

// The light in its plane's frame: a disk or rectangle as given, a sphere as the disk facing the point that
// it looks like (its silhouette cone of half-angle sigma, sin sigma = radius / distance, cut by the plane
// through its centre).
IBL_STRUCT(LightPlane) {
    vec3 center, normal, tangent, bitangent;
    float halfWidth, halfHeight; // a disk's radius is halfWidth
    uint32_t rectangle;          // 1 for a rectangle, 0 for a disk
};

// Half the light's extent along the unit direction u (its support function): the rectangle's
// |halfWidth t.u| + |halfHeight b.u|, the disk's radius sqrt(1 - (n.u)^2).
IBL_FN float lightSupport(LightPlane plane, vec3 u) {
    if (plane.rectangle != 0u)
        return plane.halfWidth * fabs(v3dot(plane.tangent, u)) +
               plane.halfHeight * fabs(v3dot(plane.bitangent, u));
    return plane.halfWidth * sqrt(saturate(1.0f - sq(v3dot(plane.normal, u))));
}

// Specular by a representative point, per unit luminance: E D' V F at one direction L.
//  Follows Drobot 1.3.4 for the point: the specular importance cone around R (eq. 1.17-1.18) is projected
//  on the light's plane as a disk, its overlap with the light found per axis (eq. 1.22-1.23; the disk in
//  light space as Drobot's square of the same width) and the overlap's centre p_sc taken as the
//  representative point (eq. 1.19). Drobot's cone is fitted to Phong; for GGX we take its apex angle from
//  eq. 1.18 through the Phong/Beckmann exponent g = 2 / alpha^2 - 2 (Walter et al. 2007): alpha(g) =
//  2 alpha, a cone of half-angle alpha. Where the horizon hides part of the light, L moves toward the
//  visible part's centroid as the footprint covers more of the light (below).
//  Departs from Drobot for the normalization: eq. 1.20 divides by the overlap area A_S, which measures a
//  Phong cone's energy, but GGX's long tails have no finite cone. Instead D' is GGX convolved with the
//  light's footprint in half-vector space, approximated at the peak by D (alpha^2 / sqrt((alpha^2 + a1^2)
//  (alpha^2 + a2^2))), a1, a2 the footprint's half-widths: the light's angular half-extents in the plane of
//  incidence and across it, halved (h = (V + L) / (2 VoH) turns L by half as much in the plane) and across
//  it divided by 2 VoH. It is Karis 2013's sphere normalization (alpha / alpha')^2, which probe.h uses for
//  the sun, with variances added instead of widths (a light smaller than the lobe then changes D by
//  O(a^2 / alpha^2), as a convolution does; Karis's sum of widths darkened r = 0.3 by 40% at 10 light sizes)
//  and the footprint anisotropic (at 80 degrees it is 1 / (2 VoH) = 3x longer across; isotropic, a
//  rectangle 57 degrees off its axis seen at 80 degrees from 10 light sizes was 31% too bright, now 6%). The
//  extents are scaled so that pi a1 a2 = E / (NoL pi): a mirror inside the light then returns exactly F L for
//  any shape and angle (D'(peak) V E = L for alpha -> 0), and a light much smaller than the lobe is the point
//  light at its centre. E is the light's illuminance with the horizon (the diffuse's), so a light sinking
//  below the horizon dims its highlight with its diffuse.
// Drobot's p_sc (above): the overlap's centre in the light's plane frame (px, py from its centre), how much
// of the light the footprint covers, and the point relative to the shading point.
IBL_STRUCT(SpecularPoint) {
    float px, py, coverage;
    vec3 toPoint;
};
IBL_FN SpecularPoint areaSpecularPoint(LightPlane plane, AreaSurface s) {
    vec3 R = v3sub(v3scale(s.N, 2.0f * v3dot(s.N, s.V)), s.V);
    float denom = v3dot(R, plane.normal);
    vec3 toCenter = v3sub(plane.center, s.P);
    float t = denom < -1e-4f ? v3dot(toCenter, plane.normal) / denom : -1.0f;
    float cx, cy, radius;
    if (t > 0.0f) { // R meets the light's plane in front: the footprint of the cone around R
        vec3 hit = v3sub(v3madd(R, t, s.P), plane.center);
        cx = v3dot(hit, plane.tangent);
        cy = v3dot(hit, plane.bitangent);
        radius = t * tan(fmin(s.alpha, 1.5f));
    } else { // R leaves the plane: the light's edge toward R
        float big = 1e4f * (plane.halfWidth + plane.halfHeight);
        cx = v3dot(R, plane.tangent) * big;
        cy = v3dot(R, plane.bitangent) * big;
        radius = 0.0f;
    }
    SpecularPoint p;
    p.px = 0.0f;
    p.py = 0.0f;
    p.coverage = 0.0f;
    if (plane.rectangle != 0u) {
        p.px = overlapCentre(cx, radius, plane.halfWidth);
        p.py = overlapCentre(cy, radius, plane.halfHeight);
        p.coverage =
            overlapCoverage(cx, radius, plane.halfWidth) * overlapCoverage(cy, radius, plane.halfHeight);
    } else {
        float rho = sqrt(cx * cx + cy * cy);
        float q = overlapCentre(rho, radius, plane.halfWidth);
        p.px = rho > 0.0f ? cx * (q / rho) : 0.0f;
        p.py = rho > 0.0f ? cy * (q / rho) : 0.0f;
        p.coverage = sq(overlapCoverage(rho, radius, plane.halfWidth));
    }
    p.toPoint = v3madd(plane.tangent, p.px, v3madd(plane.bitangent, p.py, toCenter));
    return p;
}

IBL_FN vec3 areaSpecular(LightPlane plane, AreaSurface s, float illuminance, vec3 visibleDirection) {
    SpecularPoint sc = areaSpecularPoint(plane, s);
    vec3 toCenter = v3sub(plane.center, s.P);
    float coverage = sc.coverage;
    vec3 point = sc.toPoint;
    // p_sc is the overlap's centre on the whole light; the horizon hides part of it. As the footprint covers
    // more of the light, the direction moves from p_sc's to the visible part's centroid (the clipped
    // polygon's vector irradiance), which both are when the footprint covers all of it.
    vec3 Lsc = v3safeNormalize(point, s.N);
    vec3 L =
        v3safeNormalize(v3madd(v3sub(visibleDirection, v3safeNormalize(toCenter, s.N)), coverage, Lsc), Lsc);
    vec3 H = v3safeNormalize(v3add(s.V, L), s.N);
    float NoL = saturate(v3dot(s.N, L)), NoH = saturate(v3dot(s.N, H)), LoH = saturate(v3dot(L, H));
    float alpha = fmax(s.alpha, 2e-3f); // Filament's minimum roughness keeps fp32 D finite
    // The light's half-extents across L, in the plane of incidence (inPlane) and out of it (across), scaled
    // to angles whose product is E / (pi NoL) (pi times it: the solid angle that gives the light's
    // illuminance at L's cosine); in half-vector space they shrink by 1/2 and 1 / (2 VoH).
    vec3 across = v3safeNormalize(v3cross(s.V, L), frameFromNormal(L).t);
    vec3 inPlane = v3cross(across, L);
    float extentIn = lightSupport(plane, inPlane), extentAcross = lightSupport(plane, across);
    float spread = fmin(illuminance * IBL_INV_PI / fmax(NoL, 1e-4f), 1.0f);
    float scale = extentIn * extentAcross > 0.0f ? spread / (extentIn * extentAcross) : 0.0f;
    float a2 = alpha * alpha, VoH = fmax(LoH, 1e-2f);
    float normalization = a2 / sqrt((a2 + 0.25f * scale * extentIn * extentIn) *
                                    (a2 + 0.25f * scale * extentAcross * extentAcross / (VoH * VoH)));
    float dv =
        D_GGXFromCross(v3cross(s.N, H), NoH, alpha) * normalization * V_SmithGGXCorrelated(s.NoV, NoL, alpha);
    return v3scale(fresnelSchlickRgb(s.f0, s.f90, LoH), dv * illuminance);
}

// One light seen from one surface: its plane frame, its illuminance (unit luminance, horizon included) and
// the direction of its visible part's vector irradiance. illuminance 0 where the light is behind the point
// or the point on a disk's or rectangle's plane.
IBL_STRUCT(AreaLightGeometry) {
    LightPlane plane;
    float illuminance;
    vec3 direction;
};
IBL_FN AreaLightGeometry areaLightGeometry(AreaLight light, AreaSurface s) {
    AreaLightGeometry g;
    g.illuminance = 0.0f;
    vec3 toCenter = v3sub(light.position, s.P);
    float sqrDist = v3dot(toCenter, toCenter);
    vec3 Lc = v3safeNormalize(toCenter, s.N);
    g.direction = Lc;
    float r2 = light.halfWidth * light.halfWidth;

    g.plane.center = light.position;
    g.plane.halfWidth = light.halfWidth;
    g.plane.halfHeight = light.halfHeight;
    g.plane.rectangle = light.shape == IBL_AREA_RECTANGLE ? 1u : 0u;
    float sinSigmaSqr = 0.0f; // the sphere's: sin(sigma) = radius / distance
    if (light.shape == IBL_AREA_SPHERE) {
        // The point may not enter the light (Listing 10's 0.9999).
        sinSigmaSqr = fmin(r2 / fmax(sqrDist, 1e-30f), 0.9999f);
        Frame f = frameFromNormal(v3scale(Lc, -1.0f));
        g.plane.normal = f.n;
        g.plane.tangent = f.t;
        g.plane.bitangent = f.b;
        g.plane.halfWidth = sqrt(sqrDist * sinSigmaSqr / (1.0f - sinSigmaSqr)); // d tan(sigma)
    } else {
        g.plane.normal = v3normalize(light.normal);
        g.plane.tangent = v3normalize(light.tangent);
        g.plane.bitangent = v3cross(g.plane.normal, g.plane.tangent);
        float height = -v3dot(toCenter, g.plane.normal); // of the point above the emitting face
        if (height <= 1e-6f * (light.halfWidth + light.halfHeight)) return g;
    }
    LightPlane plane = g.plane;
    // The light's outline around the point: the rectangle's corners, or a regular polygon of the disk's
    // area (circumradius r sqrt(2 pi / (n sin(2 pi / n)))).
    vec3 outline[IBL_POLYGON_MAX];
    int vertexCount = IBL_DISK_VERTICES;
    vec3 u = v3scale(plane.tangent, plane.halfWidth), w = v3scale(plane.bitangent, plane.halfHeight);
    if (plane.rectangle != 0u) {
        vertexCount = 4;
        outline[0] = v3sub(v3sub(toCenter, u), w);
        outline[1] = v3sub(v3add(toCenter, u), w);
        outline[2] = v3add(v3add(toCenter, u), w);
        outline[3] = v3add(v3sub(toCenter, u), w);
    } else {
        float c = 1.0f, sn = 0.0f, k = 1.0130016f; // k: the circumradius factor for 16 vertices
        for (int i = 0; i < IBL_DISK_VERTICES; ++i) {
            outline[i] =
                v3add(toCenter, v3scale(v3add(v3scale(plane.tangent, c), v3scale(plane.bitangent, sn)),
                                        k * plane.halfWidth));
            float cNext = c * 0.92387953f - sn * 0.38268343f; // rotation by 2 pi / 16
            sn = c * 0.38268343f + sn * 0.92387953f;
            c = cNext;
        }
    }
    PolygonIrradiance e = polygonIrradiance(outline, vertexCount, s.N, Lc);
    // The sphere's illuminance is Listing 10's exact form factor; the disk's and rectangle's the polygon's.
    g.illuminance = light.shape == IBL_AREA_SPHERE
                        ? illuminanceSphereOrDisk(clamp(v3dot(s.N, Lc), -0.999f, 0.999f), sinSigmaSqr)
                        : e.illuminance;
    g.direction = e.direction;
    return g;
}

IBL_STRUCT(AreaLightResult) {
    vec3 diffuse;
    vec3 specular;
};

// The diffuse and specular radiance toward V of a light of radiance `radiance` seen as `g`. flags:
// IBL_RT_DIFFUSE, IBL_RT_SPECULAR, IBL_RT_DISNEY_DIFFUSE (probe.h).
IBL_FN AreaLightResult areaLightShadeGeometry(AreaLightGeometry g, vec3 radiance, AreaSurface s, uint flags) {
    AreaLightResult result;
    result.diffuse = v3(0.0f, 0.0f, 0.0f);
    result.specular = v3(0.0f, 0.0f, 0.0f);
    if (g.illuminance <= 0.0f) return result;
    if ((flags & IBL_RT_DIFFUSE) != 0u) {
        float fd = 1.0f;
        if ((flags & IBL_RT_DISNEY_DIFFUSE) != 0u) { // 4.7.4, eq. 45
            float NoL = saturate(v3dot(s.N, g.direction));
            float LoH = sqrt(saturate(0.5f + 0.5f * v3dot(s.V, g.direction)));
            fd = Fr_DisneyDiffuse(s.NoV, NoL, LoH, s.perceptualRoughness);
        }
        float k = g.illuminance * fd * IBL_INV_PI;
        result.diffuse = v3(s.diffuseColor.x * radiance.x * k, s.diffuseColor.y * radiance.y * k,
                            s.diffuseColor.z * radiance.z * k);
    }
    if ((flags & IBL_RT_SPECULAR) != 0u) {
        vec3 spec = areaSpecular(g.plane, s, g.illuminance, g.direction);
        result.specular = v3(spec.x * radiance.x, spec.y * radiance.y, spec.z * radiance.z);
    }
    return result;
}

// One light on one surface: diffuse and specular radiance toward V. flags: IBL_RT_DIFFUSE,
// IBL_RT_SPECULAR, IBL_RT_DISNEY_DIFFUSE (probe.h). Zero where the light is behind the point or the point
// on a disk's or rectangle's plane; finite everywhere, inside a sphere included.
IBL_FN AreaLightResult areaLightShade(AreaLight light, AreaSurface s, uint flags) {
    return areaLightShadeGeometry(areaLightGeometry(light, s), v3scale(light.color, light.luminance), s,
                                  flags);
}

// The surface of a shading point: probe.h's material (Filament 4.8.3).
IBL_FN AreaSurface areaSurfaceFromPoint(ShadingPoint sp, float dielectricF0, uint flags) {
    AreaSurface s;
    s.P = sp.position;
    s.N = v3safeNormalize(sp.normal, v3(0.0f, 1.0f, 0.0f));
    s.V = v3safeNormalize(sp.view, s.N);
    // A view at or below the horizon is bent up to grazing, keeping its azimuth (as the reference does):
    // unbent, its mirror direction and half vectors would lie under the surface, where GGX is not defined.
    float NoV = v3dot(s.N, s.V);
    if (NoV < 1e-4f) {
        vec3 tangent = v3safeNormalize(v3sub(s.V, v3scale(s.N, NoV)), frameFromNormal(s.N).t);
        s.V = v3normalize(v3madd(s.N, 1e-4f, tangent));
    }
    s.NoV = fmax(v3dot(s.N, s.V), 1e-4f);
    s.perceptualRoughness = saturate(sp.perceptualRoughness);
    s.alpha = s.perceptualRoughness * s.perceptualRoughness;
    float metallic = saturate(sp.metallic);
    s.diffuseColor = v3scale(sp.baseColor, 1.0f - metallic);
    float dielectric = dielectricF0 * (1.0f - metallic);
    s.f0 = v3madd(sp.baseColor, metallic, v3(dielectric, dielectric, dielectric));
    s.f90 = (flags & IBL_RT_F90_FROM_F0) != 0u ? saturate(50.0f * 0.33f * (s.f0.x + s.f0.y + s.f0.z)) : 1.0f;
    return s;
}

IBL_END_NAMESPACE

#endif
