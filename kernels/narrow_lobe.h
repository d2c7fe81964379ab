// The closed form of ld.h's bright pass for a GGX lobe much narrower than a texel: integral_texel D(h) NoL dl
// as four signed triangles of the texel's projection onto the plane tangent to the lobe centre.
#ifndef IBL_NARROW_LOBE_H
#define IBL_NARROW_LOBE_H

#include "cube.h"
#include "sampling.h"

IBL_BEGIN_NAMESPACE

// atan to about 1.3 ulp (Cephes' atanf: the argument reduced to |t| <= tan(pi / 8) about 0, pi / 4 or
// pi / 2, then an odd degree-9 polynomial). lobeTriangleIntegral's two atans per edge were half of the
// bright pass on PoCL, whose atan is SLEEF's 1-ulp double-float one (~6x glibc's atanf per call).
IBL_FN float atanPolynomial(float x) {
    float a = fabs(x);
    bool big = a > 2.414213562373095f, mid = !big && a > 0.4142135623730950f;
    float offset = big ? 0.5f * IBL_PI : mid ? 0.25f * IBL_PI : 0.0f;
    float t = big ? -1.0f / a : mid ? (a - 1.0f) / (a + 1.0f) : a;
    float z = t * t;
    float p =
        (((8.05374449538e-2f * z - 1.38776856032e-1f) * z + 1.99777106478e-1f) * z - 3.33329491539e-1f) * z *
            t +
        t;
    return copysign(offset + p, x);
}

// Integral of f(q) = alpha^2 / (pi (alpha^2 + |q|^2)^2) over the triangle (0, a, b) of the plane,
// signed by the triangle's orientation. In polar form along the edge's line at distance d:
// (1 / 2 pi) (d / sqrt(alpha^2 + d^2)) [atan(d T / sqrt(alpha^2 + d^2))] between the edge's ends, T the
// tangent of the angle from the foot of the perpendicular.
IBL_FN float lobeTriangleIntegral(float2 a, float2 b, float alpha) {
    float2 e = make_float2(b.x - a.x, b.y - a.y);
    float len = sqrt(e.x * e.x + e.y * e.y);
    float cr = a.x * b.y - a.y * b.x; // twice the signed triangle area
    float d = len > 0.0f ? fabs(cr) / len : 0.0f;
    if (d <= 0.0f) return 0.0f;
    float ex = e.x / len, ey = e.y / len;
    float k = sqrt(alpha * alpha + d * d);
    float ta = (a.x * ex + a.y * ey) / d, tb = (b.x * ex + b.y * ey) / d;
    float value = (d / k) * (atanPolynomial(d * tb / k) - atanPolynomial(d * ta / k)) * (0.5f * IBL_INV_PI);
    return cr >= 0.0f ? value : -value;
}

// The corners of the face square [u0, u0 + size] x [v0, v0 + size] (face-plane coordinates) of `face`, as
// unnormalized directions, counter-clockwise from (u0, v0).
typedef struct {
    vec3 corner[4];
} FaceSquareCorners;

IBL_FN FaceSquareCorners faceSquareCorners(int face, float u0, float v0, float size) {
    FaceSquareCorners c;
    for (int k = 0; k < 4; ++k) {
        float u = u0 + ((k == 1 || k == 2) ? size : 0.0f), v = v0 + (k >= 2 ? size : 0.0f);
        c.corner[k] = cubeFaceDirection(face, 0.5f * (u + 1.0f), 0.5f * (v + 1.0f));
    }
    return c;
}

// narrowLobeTexelWeight of a texel given by its corners (brightFootprintWeight integrates one output texel
// around many lobe centres: its corners once, not per centre).
IBL_FN float narrowLobeCornersWeight(Frame frame, FaceSquareCorners texel, float alpha) {
    float2 q[4];
    for (int k = 0; k < 4; ++k) {
        vec3 inFrame = frameToLocal(frame, texel.corner[k]);
        q[k] = make_float2(0.5f * inFrame.x / inFrame.z, 0.5f * inFrame.y / inFrame.z);
    }
    float sum = 0.0f;
    for (int k = 0; k < 4; ++k)
        sum += lobeTriangleIntegral(q[k], q[(k + 1) & 3], alpha);
    return 4.0f * fabs(sum);
}

// integral_texel D(h) NoL dl for a lobe much narrower than one radian around n, texel [u0, u0 + size] x
// [v0, v0 + size] of `face` (face-plane coordinates), all of it in front of n. Small-angle form: with
// the gnomonic offset p of l in the tangent plane and q = p / 2 the half-vector offset, D(h) NoL dl ~
// 4 alpha^2 / (pi (alpha^2 + |q|^2)^2) d^2q (the total is 4 = W(0)); the texel's projection is a
// quadrilateral, integrated exactly as four signed triangles from the lobe centre.
IBL_FN float narrowLobeTexelWeight(Frame frame, int face, float u0, float v0, float size, float alpha) {
    return narrowLobeCornersWeight(frame, faceSquareCorners(face, u0, v0, size), alpha);
}

// Whether a source texel (face-plane size texelSize) at `angle` radians from a lobe of GGX alpha takes
// narrowLobeTexelWeight: the lobe under a quarter texel wide and the texel within three texels of it, and
// within half a radian, so that on coarse faces every corner stays in front of the lobe's tangent plane
// (4 px faces gave NaN without it). The bake and the fp64 reference decide alike.
IBL_FN bool narrowLobeClosedFormApplies(float alpha, float texelSize, float angle) {
    return 4.0f * alpha < texelSize && angle < fmin(3.0f * texelSize, 0.5f);
}

IBL_END_NAMESPACE

#endif
