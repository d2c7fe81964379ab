// Specular LD pre-integration with N = V = R by filtered importance sampling (Frostbite 2014,
// Listing 19 and eq. 53; Krivanek & Colbert 2008).
#ifndef IBL_LD_H
#define IBL_LD_H

#include "brdf.h"
#include "cube_sample.h"
#include "lanes.h"
#include "sampling.h"
#include "work_item.h"

IBL_BEGIN_NAMESPACE

// Kernel arguments of one LD level (fixed-width scalars; layout checked on the host).
typedef struct {
    CubePyramidLayout source;
    uint32_t faceSize;         // output face size of this level
    uint32_t sampleCount;      // table entries
    float invWeightSum;        // 1 / sum of the table's weights
    uint32_t brightCount;      // clusters of the bright-texel list
    float alpha;               // GGX alpha of this level
    float invLobeIntegral;     // 1 / W(alpha), W = integral of D(h) NoL dl (N = V)
    uint32_t brightLaneStride; // brightLaneStride(entries of the bright-texel list)
} LdParams;

// One sample of a level's table, in the texel's tangent frame: light direction, its weight NoL, and
// the source LOD whose texel solid angle matches the sample's (Listing 19). Everything here depends
// on the level only, so the host computes it once per level. IBL_LD_SAMPLE_FLOATS floats in the table,
// in this order, stored in blocks of IBL_LD_BLOCK samples component by component (the block's x, then its
// y, z, weight and lod: ldTableIndex) and padded to whole blocks with weight-0 samples, which add exact
// zeros: integrateLd reads a block's components as vectors (ld_lanes.h).
#define IBL_LD_SAMPLE_FLOATS 5
#define IBL_LD_BLOCK 8u

// Where component `component` (0..4 as above) of sample i is in a table.
IBL_FN uint ldTableIndex(uint i, uint component) {
    return IBL_LD_SAMPLE_FLOATS * IBL_LD_BLOCK * (i / IBL_LD_BLOCK) + IBL_LD_BLOCK * component +
           i % IBL_LD_BLOCK;
}
typedef struct {
    float x, y, z;
    float weight; // NoL
    float lod;
} LdSample;

// Table entry for sample i of n at GGX alpha, or weight 0 when the sample falls below the horizon.
// omegaP is the solid angle of one level-0 source texel (4 pi / (6 w^2)); lodBias is added to
// 0.5 log2(omegaS / omegaP).
IBL_FN LdSample ldSampleEntry(uint i, uint n, float alpha, float omegaP, float lodBias, float maxLod) {
    float2 u = hammersley(i, n);
    float phi = 2.0f * IBL_PI * u.y;
    vec3 h = sampleGGXHalfVector(u.x, cos(phi), sin(phi), alpha);
    vec3 l = reflectAbout(v3(0.0f, 0.0f, 1.0f), h);
    LdSample s;
    s.x = l.x;
    s.y = l.y;
    s.z = l.z;
    s.weight = fmax(l.z, 0.0f);
    // With N = V, NoH = VoH and the pdf D NoH / (4 VoH) reduces to D / 4 (Listing 19's comment).
    float pdf = D_GGX(h.z, alpha) * 0.25f;
    s.lod = prefilteredSourceLevel(n, pdf, omegaP, lodBias, maxLod);
    return s;
}

// LD for the output direction n: sum of L(l) NoL / sum of NoL over the level's table of sampleCount
// samples (a whole number of blocks), with `invWeightSum` = 1 / sum of the weights; a table block's samples
// in the lanes of float8 vectors.
#include "ld_lanes.h"

// Bright texels are taken out of the pre-filtered source and integrated exactly: with a sun 10^5 times
// brighter than the sky, the few samples of filtered importance sampling that land near it decide the
// result (noise, ghosts), and the long GGX tail carries visible energy even at low roughness. The source
// is split linearly, L = R + B: R is the source with bright texels scaled down (bright_split.h; filtered
// importance sampling handles it well), B the sparse excess, whose contribution
// sum_b B_b integral_texel D(h) NoL dl / W(alpha) is summed here over every bright texel.
// A list entry has 10 floats: centre direction (3), solid angle, excess radiance (3), face, x, y.
#define IBL_BRIGHT_ENTRY_FLOATS 10

// The entries' first IBL_BRIGHT_LANE_FLOATS floats (centre direction, solid angle, excess RGB) are also in a
// second array component by component: component c of entry i at c * brightLaneStride(count) + i, so that
// brightClusterLd reads a component of 8 consecutive entries as one vector (bright_lanes.h). The stride
// leaves room for a read of 8 from the last entry.
#define IBL_BRIGHT_LANE_FLOATS 7u

IBL_FN uint brightLaneStride(uint entryCount) {
    return (entryCount + 2u * IBL_LANES - 1u) / IBL_LANES * IBL_LANES;
}

// D(h) NoL over a sub-rectangle [u0, u0 + step] x [v0, v0 + step] (face-plane coordinates in [-1, 1])
// of one face, evaluated at its centre with its solid angle.
IBL_FN float lobeWeightOfPatch(vec3 n, int face, float u0, float v0, float step, float alpha) {
    float omega = cubePatchSolidAngle(u0, v0, step);
    vec3 l = v3normalize(
        cubeFaceDirection(face, 0.5f * (u0 + 0.5f * step + 1.0f), 0.5f * (v0 + 0.5f * step + 1.0f)));
    float NoL = v3dot(n, l);
    vec3 h = v3normalize(v3add(n, l));
    return NoL > 0.0f ? D_GGX(v3dot(n, h), alpha) * NoL * omega : 0.0f;
}

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

// sum over the S x S patches of the bright texel [bu, bu + S step] x [bv, bv + S step] of sourceFace of their
// solid angle times narrowLobeCornersWeight of `texel` around their centre (brightFootprintWeight), with the
// patches in vector lanes.
#include "narrow_lobe_lanes.h"

// Whether a source texel (face-plane size texelSize) at `angle` radians from a lobe of GGX alpha takes
// narrowLobeTexelWeight: the lobe under a quarter texel wide and the texel within three texels of it, and
// within half a radian, so that on coarse faces every corner stays in front of the lobe's tangent plane
// (4 px faces gave NaN without it). The bake and the fp64 reference decide alike.
IBL_FN bool narrowLobeClosedFormApplies(float alpha, float texelSize, float angle) {
    return 4.0f * alpha < texelSize && angle < fmin(3.0f * texelSize, 0.5f);
}

// The angle between two unit directions whose cosine is cosAngle, as their chord: accurate where it matters
// (small angles), and no acos.
IBL_FN float chordAngle(float cosAngle) {
    return sqrt(fmax(0.0f, 2.0f - 2.0f * cosAngle));
}

// integral_texel D(h) NoL dl of one bright-list entry for the lobe around n (unnormalized).
IBL_FN_INLINED float brightTexelWeight(vec3 n, Frame frame, IBL_GLOBAL const float* e, float alpha,
                                       float texelSize) {
    // The midpoint rule over a texel of size a at angle theta from the lobe centre errs by about
    // (a / theta)^2 in GGX's theta^-4 tail, so texels nearer than 10 texels are integrated on an S x S
    // grid, S = 10 a / max(theta, alpha) (error ~1%). Near a lobe under a quarter texel wide the closed
    // form is used instead (narrowLobeClosedFormApplies).
    vec3 d = v3(e[0], e[1], e[2]);
    float cosAngle = v3dot(n, d);
    float angle = chordAngle(cosAngle);
    float subdivisions = ceil(10.0f * texelSize / fmax(angle, alpha));
    int face = (int)e[7];
    float u0 = -1.0f + e[8] * texelSize, v0 = -1.0f + e[9] * texelSize;
    if (narrowLobeClosedFormApplies(alpha, texelSize, angle))
        return narrowLobeTexelWeight(frame, face, u0, v0, texelSize, alpha);
    if (subdivisions <= 1.0f || cosAngle < 0.0f) {
        vec3 h = v3normalize(v3add(n, d));
        return cosAngle > 0.0f ? D_GGX(v3dot(n, h), alpha) * cosAngle * e[3] : 0.0f;
    }
    int S = (int)fmin(subdivisions, 32.0f);
    float step = texelSize / (float)S, weight = 0.0f;
    for (int j = 0; j < S; ++j)
        for (int k = 0; k < S; ++k)
            weight += lobeWeightOfPatch(n, face, u0 + (float)k * step, v0 + (float)j * step, step, alpha);
    return weight;
}

// Patch (j, k) of an S x S grid of step `step` over the output texel at (u0, v0) of `face`: its solid angle
// times the lobe around its centre over bright entry e (brightTexelWeight).
IBL_FN float footprintPatchWeight(int face, float u0, float v0, float step, int j, int k,
                                  IBL_GLOBAL const float* e, float alpha, float sourceTexelSize) {
    float pu = u0 + (float)k * step, pv = v0 + (float)j * step;
    vec3 n = v3normalize(
        cubeFaceDirection(face, 0.5f * (pu + 0.5f * step + 1.0f), 0.5f * (pv + 0.5f * step + 1.0f)));
    return cubePatchSolidAngle(pu, pv, step) *
           brightTexelWeight(n, frameFromNormal(n), e, alpha, sourceTexelSize);
}

// The sum of footprintPatchWeight over the S x S grid, with the patches in vector lanes.
#include "footprint_lanes.h"

// Footprint-averaged bright texels. Where the lobe is narrower than an output texel, LD at the texel centre
// sees a sub-texel sun or misses it: a level's energy then depends on where the sun falls (at a cube edge /
// corner, 0.50 / 1.36 of the source's at 64 px) and a rotating map pulses. Such a texel t stores LD averaged
// over its own solid angle Omega_t instead, whose bright part is
//   sum_b B_b integral_b G_t(l) dl / (Omega_t W),  G_t(l) = integral_t D(h) (n.l) dn,
// since D(h) (n.l), h = normalize(n + l), is symmetric in n and l: G_t is the lobe around l integrated over
// the output texel, and summed over every t it is W for every l, so a level keeps its source's energy.
// "Narrower": the lobe's reflected directions (about 2 alpha wide) under one texel (2 / n face-plane units).
IBL_FN bool ldFootprintApplies(float alpha, uint outputFaceSize) {
    return 2.0f * alpha < 2.0f / (float)outputFaceSize;
}

// The angle from unit direction n to bright entry e's centre (chordAngle).
IBL_FN float brightEntryAngle(vec3 n, IBL_GLOBAL const float* e) {
    return chordAngle(v3dot(n, v3(e[0], e[1], e[2])));
}

// Whether LD averaged over output texel t's footprint (face-plane size outSize) needs more than its value at
// t's centre for bright entry e at `angle` from it: within three texels of t. Farther, the average is the
// centre's value.
IBL_FN bool brightEntryNearFootprint(float angle, float outSize) {
    return angle < 3.0f * outSize;
}

// integral_b G_t(l) dl for bright entry e within three texels of output texel t (face, corner (u0, v0),
// face-plane size outSize, e's centre at `angle` from t's centre).
// - With a lobe under a quarter of t: b in S x S patches, each its solid angle times
//   narrowLobeTexelWeight's closed form of G_t around its centre; G_t varies over about alpha near t's
//   edges, so S = 4 source texel / alpha, up to 16, for the bright texels within about a texel of t (the
//   midpoint rule converges only linearly across an edge it does not resolve: up to 8, the texels beside
//   a sun on rooitou's 32-px level 1 read 1.2% off), and 1 beyond.
// - With a wider lobe: t in S x S patches, each its solid angle times the lobe around its centre over b
//   (brightTexelWeight), S ~ 2 outSize / alpha (2 to 8).
IBL_FN float brightFootprintWeight(int face, float u0, float v0, float outSize, float angle,
                                   IBL_GLOBAL const float* e, float alpha, float sourceTexelSize) {
    if (narrowLobeClosedFormApplies(alpha, outSize, angle)) {
        // Only a bright texel touching t (or a texel away) has t's edges across it.
        int S = angle < outSize + sourceTexelSize
                    ? (int)clamp(ceil(4.0f * sourceTexelSize / alpha), 1.0f, 16.0f)
                    : 1;
        int sourceFace = (int)e[7];
        float step = sourceTexelSize / (float)S;
        float bu = -1.0f + e[8] * sourceTexelSize, bv = -1.0f + e[9] * sourceTexelSize;
        return narrowFootprintPatchesWeight(faceSquareCorners(face, u0, v0, outSize), sourceFace, bu, bv,
                                            step, S, alpha);
    }
    int S = (int)clamp(ceil(2.0f * outSize / alpha), 2.0f, 8.0f);
    return footprintPatchesWeight(face, u0, v0, outSize / (float)S, S, e, alpha, sourceTexelSize);
}

// Bright texels are grouped into clusters (IBL_BRIGHT_CLUSTER_FLOATS each: centroid direction (3),
// angular radius, bound on sum of excess * solid angle (max over channels), first entry, entry count,
// cosine of half the angular radius). A cluster whose largest possible contribution, D at its nearest point
// times its energy, stays under `skipBelow` is skipped: the caller sets skipBelow to 1e-3 of the texel's
// sampled value divided by the cluster count, so all skipped clusters together change a texel by under 0.1%.
// The bright part of output texel (face, x, y) of an n-texel level: at its centre, or over its footprint
// where ldFootprintApplies.
#define IBL_BRIGHT_CLUSTER_FLOATS 8

// cos(max(angle - radius - reach, 0) / 2) for a direction at cosine cosAngle from a cluster's centroid: the
// half-angle of the nearest point of the cluster widened by reach (1 within it), from the half angles'
// cosines and sines by the angle-difference identity. Square roots only: acos and cos per cluster and
// texel were a large part of the bright pass on PoCL, whose acos/cos are SLEEF's.
IBL_FN float cosHalfNearestAngle(float cosAngle, float cosHalfRadius, float cosHalfReach,
                                 float sinHalfReach) {
    float sinHalfRadius = sqrt(fmax(0.0f, 1.0f - cosHalfRadius * cosHalfRadius));
    float cosHalfBound =
        cosHalfRadius * cosHalfReach - sinHalfRadius * sinHalfReach; // of (radius + reach) / 2
    float sinHalfBound = sinHalfRadius * cosHalfReach + cosHalfRadius * sinHalfReach;
    float cosHalf = sqrt(fmax(0.0f, 0.5f * (1.0f + cosAngle)));
    float sinHalf = sqrt(fmax(0.0f, 0.5f * (1.0f - cosAngle)));
    // Half angles lie in [0, pi / 2], where cos falls: within the widened cluster iff cosHalf >=
    // cosHalfBound.
    return cosHalf >= cosHalfBound ? 1.0f : cosHalf * cosHalfBound + sinHalf * sinHalfBound;
}

// An output texel of the bright pass: its centre direction and frame, and its square (face, corner (u0, v0),
// face-plane size) with whether LD is averaged over it (ldFootprintApplies).
typedef struct {
    vec3 centre;
    Frame frame;
    int face;
    float u0, v0, size;
    int footprint;
    float solidAngle; // Omega_t, or -1 until a bright entry near the footprint needs it
} BrightTarget;

// The weight of bright entry e for output texel t (brightTexelsLd divides it by W).
IBL_FN float brightEntryWeight(BrightTarget* t, IBL_GLOBAL const float* e, float alpha, float texelSize) {
    float angle = t->footprint ? brightEntryAngle(t->centre, e) : 0.0f;
    if (t->footprint && brightEntryNearFootprint(angle, t->size)) {
        // Omega_t when an entry is first near the footprint (few texels have one; four atan2).
        if (t->solidAngle < 0.0f) t->solidAngle = cubePatchSolidAngle(t->u0, t->v0, t->size);
        return brightFootprintWeight(t->face, t->u0, t->v0, t->size, angle, e, alpha, texelSize) /
               t->solidAngle;
    }
    // No footprint, or one whose average over t is the value at its centre.
    return brightTexelWeight(t->centre, t->frame, e, alpha, texelSize);
}

// The sum of the entries [first, first + count) of a cluster weighted by brightEntryWeight, with the entries
// in vector lanes where each takes its point value.
#include "bright_lanes.h"

IBL_FN vec3 brightTexelsLd(int face, uint x, uint y, uint n, IBL_GLOBAL const float* clusters,
                           uint clusterCount, IBL_GLOBAL const float* bright,
                           IBL_GLOBAL const float* brightLanes, uint laneStride, float alpha,
                           float invLobeIntegral, uint sourceFaceSize, float skipBelow) {
    float texelSize = 2.0f / (float)sourceFaceSize;
    BrightTarget t;
    t.centre = cubeTexelDirection(face, x, y, n);
    t.frame = frameFromNormal(t.centre);
    t.face = face;
    t.size = 2.0f / (float)n;
    t.u0 = -1.0f + (float)x * t.size;
    t.v0 = -1.0f + (float)y * t.size;
    t.footprint = ldFootprintApplies(alpha, n);
    t.solidAngle = -1.0f;
    // A footprint reaches half a diagonal (~0.71 size radians or less) from its centre.
    float reach = t.footprint ? 0.71f * t.size : 0.0f;
    float cosHalfReach = cos(0.5f * reach), sinHalfReach = sin(0.5f * reach);
    vec3 sum = v3(0.0f, 0.0f, 0.0f);
    for (uint c = 0; c < clusterCount; ++c) {
        const IBL_GLOBAL float* cl = clusters + IBL_BRIGHT_CLUSTER_FLOATS * c;
        float cosAngle = t.centre.x * cl[0] + t.centre.y * cl[1] + t.centre.z * cl[2];
        // D at the nearest member (D falls with theta_h, half the angle to it) times the cluster's energy.
        float bound = D_GGX(cosHalfNearestAngle(cosAngle, cl[7], cosHalfReach, sinHalfReach), alpha) * cl[4] *
                      invLobeIntegral;
        if (bound < skipBelow) continue;
        sum = v3add(sum, brightClusterLd(&t, bright, brightLanes, laneStride, (uint)cl[5], (uint)cl[6], alpha,
                                         texelSize));
    }
    return v3scale(sum, invLobeIntegral);
}

// The skip threshold for a texel whose sampled (residual) value is `sampled`.
IBL_FN float brightSkipThreshold(vec3 sampled, uint clusterCount) {
    float value = fmax(sampled.x, fmax(sampled.y, sampled.z));
    return clusterCount > 0u ? 1e-3f * value / (float)clusterCount : 0.0f;
}

// The work-items of ld.cl and of the CPU backend (ld_host_items.cpp), one texel of one level
// (iblbake/opencl/dispatch.h): ldLevelItem stores the sampled part, ldBrightItem then adds the exactly
// integrated bright texels to it. Two kernels, so that the filtered-importance-sampling loop stays uniform
// and simple enough for PoCL to vectorize.
IBL_FN void ldLevelItem(WorkItem t, IBL_GLOBAL float* out, LdParams params, IBL_GLOBAL const float* pyramid,
                        IBL_GLOBAL const float* table) {
    storeTexel(out, t,
               integrateLd(cubeWorkItemDirection(t, params.faceSize), pyramid, params.source, table,
                           params.sampleCount, params.invWeightSum));
}

// A texel's sampled part plus its bright texels, as ldBrightItem adds them to the stored sampled part.
IBL_FN vec3 ldWithBrightTexels(WorkItem t, vec3 sampled, LdParams params, IBL_GLOBAL const float* clusters,
                               IBL_GLOBAL const float* bright, IBL_GLOBAL const float* brightLanes) {
    float skipBelow = brightSkipThreshold(sampled, params.brightCount);
    return v3add(sampled, brightTexelsLd((int)t.face, t.x, t.y, params.faceSize, clusters, params.brightCount,
                                         bright, brightLanes, params.brightLaneStride, params.alpha,
                                         params.invLobeIntegral, params.source.baseFaceSize, skipBelow));
}

IBL_FN void ldBrightItem(WorkItem t, IBL_GLOBAL float* out, LdParams params, IBL_GLOBAL const float* clusters,
                         IBL_GLOBAL const float* bright, IBL_GLOBAL const float* brightLanes) {
    storeTexel(out, t, ldWithBrightTexels(t, loadTexel(out, t), params, clusters, bright, brightLanes));
}

// Levels of at most IBL_LD_ONE_PASS_FACE_SIZE texels a side (at most 96 texels) take both parts in one
// work-item and one dispatch: so few items leave nothing for a vectorizer across them, and PoCL's 4-, 2- and
// 1-px levels went from 1.79, 1.00, 0.49 to 1.58, 0.95, 0.48 ms (bench bakeChainLevels, medians of 7). The
// sampled part stays in registers, so the item still reads no output of its own, and the sum is the same
// float addition as the two passes' (the same bytes).
#define IBL_LD_ONE_PASS_FACE_SIZE 4u

IBL_FN void ldOnePassItem(WorkItem t, IBL_GLOBAL float* out, LdParams params, IBL_GLOBAL const float* pyramid,
                          IBL_GLOBAL const float* table, IBL_GLOBAL const float* clusters,
                          IBL_GLOBAL const float* bright, IBL_GLOBAL const float* brightLanes) {
    storeTexel(out, t,
               ldWithBrightTexels(t,
                                  integrateLd(cubeWorkItemDirection(t, params.faceSize), pyramid,
                                              params.source, table, params.sampleCount, params.invWeightSum),
                                  params, clusters, bright, brightLanes));
}

IBL_END_NAMESPACE

#endif
