// For brightFootprintWeight (bright_entry_weight.h): narrowFootprintPatchesWeight with IBL_LANES patches of
// the bright texel in the lanes of float8 vectors (lanes.h). The patches of a sun texel next to an output
// texel on faces under a quarter-texel lobe (up to 16 x 16 of them, each four lobeTriangleIntegral) were four
// fifths of the bright pass of a 128 px level on PoCL, which ran them scalar. Same arithmetic as
// cubeFaceDirection, v3normalize, frameFromNormal, frameToLocal, narrowLobeCornersWeight,
// lobeTriangleIntegral, atanPolynomial and cubePatchSolidAngle, lane by lane.
#ifndef IBL_NARROW_LOBE_LANES_H
#define IBL_NARROW_LOBE_LANES_H

#include "lanes.h"
#include "narrow_lobe.h"

IBL_BEGIN_NAMESPACE

IBL_FN float8 atanPolynomialLanes(float8 x) {
    float8 a = fabs(x);
    int8 big = isgreater(a, 2.414213562373095f), mid = ~big & isgreater(a, 0.4142135623730950f);
    float8 offset = select(select((float8)0.0f, (float8)(0.25f * IBL_PI), mid), (float8)(0.5f * IBL_PI), big);
    float8 t = select(select(a, (a - 1.0f) / (a + 1.0f), mid), -1.0f / a, big);
    float8 z = t * t;
    float8 p =
        (((8.05374449538e-2f * z - 1.38776856032e-1f) * z + 1.99777106478e-1f) * z - 3.33329491539e-1f) * z *
            t +
        t;
    return copysign(offset + p, x);
}

// lobeTriangleIntegral of the triangles (0, a, b).
IBL_FN float8 lobeTriangleIntegralLanes(float8 ax, float8 ay, float8 bx, float8 by, float alpha) {
    float8 ex = bx - ax, ey = by - ay;
    float8 len = sqrt(ex * ex + ey * ey);
    float8 cr = ax * by - ay * bx;
    float8 d = select((float8)0.0f, fabs(cr) / len, isgreater(len, 0.0f));
    float8 unitX = ex / len, unitY = ey / len;
    float8 k = sqrt(alpha * alpha + d * d);
    float8 ta = (ax * unitX + ay * unitY) / d, tb = (bx * unitX + by * unitY) / d;
    float8 value =
        (d / k) * (atanPolynomialLanes(d * tb / k) - atanPolynomialLanes(d * ta / k)) * (0.5f * IBL_INV_PI);
    // Degenerate lanes (d = 0) computed NaNs above; they are replaced, not summed.
    return select(select(-value, value, isgreaterequal(cr, 0.0f)), (float8)0.0f, islessequal(d, 0.0f));
}

// sum over the S x S patches of the bright texel [bu, bu + S step] x [bv, bv + S step] of sourceFace of
// their solid angle times narrowLobeCornersWeight of `texel` around their centre.
IBL_FN float narrowFootprintPatchesWeight(FaceSquareCorners texel, int sourceFace, float bu, float bv,
                                          float step, int S, float alpha) {
    float8 sum = 0.0f;
    for (int first = 0; first < S * S; first += (int)IBL_LANES) {
        PatchLanes p = patchLanes(sourceFace, bu, bv, step, S, first);
        float8 nx = p.nx, ny = p.ny, nz = p.nz;
        // frameFromNormal(n): tangent (tx, ty, tz), bitangent (bx, by, bz).
        float8 s = copysign((float8)1.0f, nz);
        float8 a = -1.0f / (s + nz);
        float8 b = nx * ny * a;
        float8 tx = 1.0f + s * nx * nx * a, ty = s * b, tz = -s * nx;
        float8 bx = b, by = s + ny * ny * a, bz = -ny;
        // narrowLobeCornersWeight: the corners' gnomonic offsets in the frame, then four triangles.
        float8 qx[4], qy[4];
        for (int k = 0; k < 4; ++k) {
            vec3 c = texel.corner[k];
            float8 lx = c.x * tx + c.y * ty + c.z * tz, ly = c.x * bx + c.y * by + c.z * bz;
            float8 lz = c.x * nx + c.y * ny + c.z * nz;
            qx[k] = 0.5f * lx / lz;
            qy[k] = 0.5f * ly / lz;
        }
        float8 triangles = 0.0f;
        for (int k = 0; k < 4; ++k)
            triangles += lobeTriangleIntegralLanes(qx[k], qy[k], qx[(k + 1) & 3], qy[(k + 1) & 3], alpha);
        sum += select((float8)0.0f, p.solidAngle * (4.0f * fabs(triangles)), p.inGrid);
    }
    return sumLanes(sum);
}

IBL_END_NAMESPACE

#endif
