// Low-discrepancy points and the samplers shared by the bake stages and the reference integrators.
// The functions that turn a point into a direction take the texel-independent parts (disk
// coordinates, cos/sin of the azimuth) precomputed, so that a bake kernel's inner loop is free of
// transcendentals: tables are built once per level on the host from these same functions.
#ifndef IBL_SAMPLING_H
#define IBL_SAMPLING_H

#include "portable.h"

IBL_BEGIN_NAMESPACE

// The 32 bits of `bits` in reverse order.
IBL_FN uint reverseBits32(uint bits) {
    bits = (bits << 16u) | (bits >> 16u);
    bits = ((bits & 0x55555555u) << 1u) | ((bits & 0xAAAAAAAAu) >> 1u);
    bits = ((bits & 0x33333333u) << 2u) | ((bits & 0xCCCCCCCCu) >> 2u);
    bits = ((bits & 0x0F0F0F0Fu) << 4u) | ((bits & 0xF0F0F0F0u) >> 4u);
    return ((bits & 0x00FF00FFu) << 8u) | ((bits & 0xFF00FF00u) >> 8u);
}

// Van der Corput radical inverse in base 2 by bit reversal.
IBL_FN float radicalInverse2(uint bits) {
    return IBL_FLOAT(reverseBits32(bits)) * 2.3283064365386963e-10f;
}

// Hammersley point i of n in [0,1)^2 (first coordinate centred in its stratum).
IBL_FN float2 hammersley(uint i, uint n) {
    return make_float2((IBL_FLOAT(i) + 0.5f) / IBL_FLOAT(n), radicalInverse2(i));
}

// Point of the unit disk with area-uniform density: sqrt(u1) (cos 2 pi u2, sin 2 pi u2).
IBL_FN float2 unitDiskPoint(float2 u) {
    float r = sqrt(u.x), phi = 2.0f * IBL_PI * u.y;
    return make_float2(r * cos(phi), r * sin(phi));
}

IBL_STRUCT(Frame) {
    vec3 t; // tangent
    vec3 b; // bitangent
    vec3 n; // normal
};

// Orthonormal basis around n, continuous and stable at the poles (Duff et al. 2017, "Building an
// Orthonormal Basis, Revisited"), unlike the up-vector switch of Frostbite's importanceSampleCosDir.
IBL_FN Frame frameFromNormal(vec3 n) {
    float s = copysign(1.0f, n.z);
    float a = -1.0f / (s + n.z);
    float b = n.x * n.y * a;
    Frame f;
    f.t = v3(1.0f + s * n.x * n.x * a, s * b, -s * n.x);
    f.b = v3(b, s + n.y * n.y * a, -n.y);
    f.n = n;
    return f;
}

IBL_FN vec3 frameToWorld(Frame f, vec3 v) {
    return v3madd(f.t, v.x, v3madd(f.b, v.y, v3scale(f.n, v.z)));
}
IBL_FN vec3 frameToLocal(Frame f, vec3 v) {
    return v3(v3dot(v, f.t), v3dot(v, f.b), v3dot(v, f.n));
}

// cos(theta_h) of a GGX NDF sample: inverting the CDF of D(h) cos(theta_h) (Walter et al. 2007).
IBL_FN float ggxSampleCosTheta(float u1, float alpha) {
    float a2 = alpha * alpha;
    return sqrt(fmax(0.0f, (1.0f - u1) / (1.0f + (a2 - 1.0f) * u1)));
}

// GGX NDF half vector in tangent space (z = normal), with the azimuth's cos/sin given.
IBL_FN vec3 sampleGGXHalfVector(float u1, float cosPhi, float sinPhi, float alpha) {
    float cosTheta = ggxSampleCosTheta(u1, alpha);
    float sinTheta = sqrt(fmax(0.0f, 1.0f - cosTheta * cosTheta));
    return v3(sinTheta * cosPhi, sinTheta * sinPhi, cosTheta);
}

// Per-view part of GGX VNDF sampling (Heitz 2018, "Sampling the GGX Distribution of Visible Normals"):
// the view in the hemisphere configuration and its orthonormal basis.
IBL_STRUCT(VndfView) {
    vec3 vh;
    vec3 t1;
    vec3 t2;
    float alpha;
};

IBL_FN VndfView vndfPrepare(vec3 viewLocal, float alpha) {
    VndfView p;
    p.alpha = alpha;
    p.vh = v3normalize(v3(alpha * viewLocal.x, alpha * viewLocal.y, viewLocal.z));
    float lensq = p.vh.x * p.vh.x + p.vh.y * p.vh.y;
    float inv = lensq > 0.0f ? 1.0f / sqrt(lensq) : 0.0f;
    p.t1 = lensq > 0.0f ? v3(-p.vh.y * inv, p.vh.x * inv, 0.0f) : v3(1.0f, 0.0f, 0.0f);
    p.t2 = v3cross(p.vh, p.t1);
    return p;
}

// vndfPrepare for a view in the xz-plane (v.y = 0, v.x >= 0), the case of every isotropic
// pre-integration: t1 = +y in closed form, which keeps the per-texel setup free of branches.
IBL_FN VndfView vndfPrepareXZ(vec3 viewLocal, float alpha) {
    VndfView p;
    p.alpha = alpha;
    p.vh = v3normalize(v3(alpha * viewLocal.x, 0.0f, viewLocal.z));
    p.t1 = v3(0.0f, 1.0f, 0.0f);
    p.t2 = v3(-p.vh.z, 0.0f, p.vh.x); // vh x t1
    return p;
}

// Visible normal (tangent space) for a unit-disk point (Heitz 2018, listing 1).
IBL_FN vec3 vndfSample(VndfView p, float diskX, float diskY) {
    float s = 0.5f * (1.0f + p.vh.z);
    float t1 = diskX;
    float t2 = (1.0f - s) * sqrt(fmax(0.0f, 1.0f - t1 * t1)) + s * diskY;
    float t3 = sqrt(fmax(0.0f, 1.0f - t1 * t1 - t2 * t2));
    vec3 nh = v3madd(p.t1, t1, v3madd(p.t2, t2, v3scale(p.vh, t3)));
    return v3normalize(v3(p.alpha * nh.x, p.alpha * nh.y, fmax(1e-7f, nh.z)));
}

// Cosine-weighted direction in tangent space from a unit-disk point (Malley's method); pdf = cos / pi.
IBL_FN vec3 cosineSampleFromDisk(float diskX, float diskY) {
    return v3(diskX, diskY, sqrt(fmax(0.0f, 1.0f - diskX * diskX - diskY * diskY)));
}

// Mirror of v about h (both unit): 2 (v.h) h - v.
IBL_FN vec3 reflectAbout(vec3 v, vec3 h) {
    return v3sub(v3scale(h, 2.0f * v3dot(v, h)), v);
}

IBL_END_NAMESPACE

#endif
