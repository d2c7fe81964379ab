// Real spherical harmonics up to L2 (9 coefficients per channel), docs/conventions.md "SH": order
// (l,m) = (0,0), (1,-1), (1,0), (1,1), (2,-2), (2,-1), (2,0), (2,1), (2,2), standard (orthonormal)
// normalization, Y_i(d) = k_i p_i(d) for a unit direction d with the polynomials
//   p = 1, y, z, x, xy, yz, 3z^2 - 1, xz, x^2 - y^2
// that Filament's irradianceSH(n) uses (Filament 5.3.4.1). Convolution with the clamped cosine
// max(0, cos) multiplies band l by A_l = pi, 2 pi / 3, pi / 4 (Ramamoorthi & Hanrahan 2001), so
// E(n) = sum_i A_l(i) L_i Y_i(n) = sum_i (A_l(i) k_i L_i) p_i(n): the "pre-scaled" irradiance
// coefficients A_l k_i L_i are what irradianceSH evaluates with nothing but the polynomials.
#ifndef IBL_SH_H
#define IBL_SH_H

#include "portable.h"

IBL_BEGIN_NAMESPACE

#define IBL_SH_COUNT 9

// k_i of Y_i = k_i p_i.
#define IBL_SH_K00 0.28209479177387814f // 1 / (2 sqrt(pi))
#define IBL_SH_K1 0.48860251190291992f  // sqrt(3 / (4 pi)): (1,-1), (1,0), (1,1)
#define IBL_SH_K2 1.09254843059207907f  // sqrt(15 / (4 pi)): (2,-2), (2,-1), (2,1)
#define IBL_SH_K20 0.31539156525252001f // sqrt(5 / (16 pi))
#define IBL_SH_K22 0.54627421529603954f // sqrt(15 / (16 pi))

// Clamped-cosine convolution factor A_l of each band.
#define IBL_SH_A0 3.14159265358979323846f // pi
#define IBL_SH_A1 2.09439510239319549231f // 2 pi / 3
#define IBL_SH_A2 0.78539816339744830962f // pi / 4

typedef struct {
    float v[IBL_SH_COUNT];
} ShBasis;

// Band l of coefficient i (0, 1, 1, 1, 2, 2, 2, 2, 2).
IBL_FN int shBand(int i) {
    return i == 0 ? 0 : (i < 4 ? 1 : 2);
}

IBL_FN float shBasisConstant(int i) {
    return i == 0 ? IBL_SH_K00 : i < 4 ? IBL_SH_K1 : i == 6 ? IBL_SH_K20 : i == 8 ? IBL_SH_K22 : IBL_SH_K2;
}

IBL_FN float shClampedCosineFactor(int band) {
    return band == 0 ? IBL_SH_A0 : band == 1 ? IBL_SH_A1 : IBL_SH_A2;
}

// The polynomials p_i(d) of Filament's irradianceSH, for a unit direction.
IBL_FN ShBasis shPolynomials(vec3 d) {
    ShBasis p;
    p.v[0] = 1.0f;
    p.v[1] = d.y;
    p.v[2] = d.z;
    p.v[3] = d.x;
    p.v[4] = d.x * d.y;
    p.v[5] = d.y * d.z;
    p.v[6] = 3.0f * d.z * d.z - 1.0f;
    p.v[7] = d.x * d.z;
    p.v[8] = d.x * d.x - d.y * d.y;
    return p;
}

// Y_i(d) for a unit direction d.
IBL_FN ShBasis shBasis(vec3 d) {
    ShBasis y = shPolynomials(d);
    for (int i = 0; i < IBL_SH_COUNT; ++i)
        y.v[i] *= shBasisConstant(i);
    return y;
}

// sum_i sh_i w_i over RGB coefficients stored as 27 floats (coefficient i's RGB at 3i..3i+2).
IBL_FN vec3 shWeightedSum(IBL_GLOBAL const float* sh, ShBasis w) {
    float r = 0.0f, g = 0.0f, b = 0.0f;
    for (int i = 0; i < IBL_SH_COUNT; ++i) {
        r += sh[3 * i] * w.v[i];
        g += sh[3 * i + 1] * w.v[i];
        b += sh[3 * i + 2] * w.v[i];
    }
    return v3(r, g, b);
}

// Filament's irradianceSH(n): sum_i sh_i p_i(n) with `sh` 27 floats, coefficient i's RGB at 3i..3i+2.
// With the pre-scaled irradiance coefficients A_l k_i L_i it returns E(n); with those divided by pi
// (the Lambert 1/pi folded in, Filament's cmgen convention) it returns E(n) / pi.
IBL_FN vec3 shEvalPrescaled(IBL_GLOBAL const float* sh, vec3 n) {
    return shWeightedSum(sh, shPolynomials(n));
}

// The radiance SH L_i (not pre-scaled) evaluated at n: sum_i L_i Y_i(n), same 27-float layout.
IBL_FN vec3 shEvalRadiance(IBL_GLOBAL const float* sh, vec3 n) {
    return shWeightedSum(sh, shBasis(n));
}

IBL_END_NAMESPACE

#endif
