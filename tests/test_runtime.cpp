// Runtime probe sampling: the Frostbite listings it reproduces, white furnace, analytic rooms for local
// probes (box and sphere proxies, capture offsets), composition, influence, degenerate inputs, loading
// from KTX2, OpenCL vs CPU agreement and throughput.
#include "room_test_support.h"
#include "runtime_test_support.h"

#include <iblbake/core/error.h>
#include <iblbake/ktx2/ktx2.h>

#include <chrono>
#include <filesystem>
#include <random>

#include <unistd.h>

#include <glm/gtc/matrix_transform.hpp>

namespace {

using namespace ibl;
using namespace rt_test;

// ------------------------------------------------------------------------------------------------
// Listing 25, transcribed verbatim (HLSL clamp and lerp), against the runtime's function.

float hlslLerp(float x, float y, float s) {
    return x + s * (y - x);
}
float hlslClamp(float x, float lo, float hi) {
    return std::min(std::max(x, lo), hi);
}
float listing25(float distIntersectionToShadedPoint, float distIntersectionToProbeCenter,
                float linearRoughness) {
    float newLinearRoughness = hlslClamp(
        distIntersectionToShadedPoint / distIntersectionToProbeCenter * linearRoughness, 0, linearRoughness);
    return hlslLerp(newLinearRoughness, linearRoughness, linearRoughness);
}

TEST(Listing25, ReproducedExactly) {
    long compared = 0;
    for (float d1 = 0.0f; d1 <= 20.0f; d1 += 0.173f)
        for (float d2 = 0.001f; d2 <= 20.0f; d2 = d2 * 1.37f + 0.01f)
            for (int k = 0; k <= 40; ++k) {
                float r = k / 40.0f;
                float expected = listing25(d1, d2, r);
                float got = computeDistanceBaseRoughness(d1, d2, r);
                ASSERT_EQ(got, expected) << d1 << " " << d2 << " " << r; // bit for bit
                ++compared;
            }
    // By hand: d1/d2 = 0.5, r = 0.5 -> clamp(0.25, 0, 0.5) = 0.25 -> 0.25 + 0.5 (0.5 - 0.25) = 0.375.
    EXPECT_FLOAT_EQ(computeDistanceBaseRoughness(1.0f, 2.0f, 0.5f), 0.375f);
    // Far wall (ratio >= 1): the roughness itself; mirror stays mirror; r = 1 stays 1.
    EXPECT_EQ(computeDistanceBaseRoughness(5.0f, 1.0f, 0.3f), 0.3f);
    EXPECT_EQ(computeDistanceBaseRoughness(0.1f, 3.0f, 0.0f), 0.0f);
    EXPECT_EQ(computeDistanceBaseRoughness(0.1f, 3.0f, 1.0f), 1.0f);
    // Receiver on the wall: r^2. Intersection at the capture point (d2 = 0): the limit r, finite.
    EXPECT_FLOAT_EQ(computeDistanceBaseRoughness(0.0f, 2.0f, 0.6f), 0.36f);
    EXPECT_EQ(computeDistanceBaseRoughness(1.0f, 0.0f, 0.6f), 0.6f);
    EXPECT_EQ(computeDistanceBaseRoughness(1.0f, 0.0f, 0.0f), 0.0f);
    std::printf("Listing 25: %ld inputs bit-identical\n", compared);
}

// The mean direction of the lobe f(v, l) <n.l> (F = 1, height-correlated Smith), by importance sampling
// D(h) <n.h> with Hammersley points: weight V(v, l) <v.h> <n.l> / <n.h> per sample.
glm::dvec3 lobeMeanDirection(float NoV, float alpha) {
    const glm::dvec3 v(std::sqrt(std::max(0.0, 1.0 - double(NoV) * NoV)), 0.0, NoV);
    const uint32_t count = 1u << 16;
    glm::dvec3 sum(0.0);
    for (uint32_t i = 0; i < count; ++i) {
        const float2 u = hammersley(i, count);
        const float phi = 2.0f * IBL_PI * u.y;
        const vec3 h = sampleGGXHalfVector(u.x, std::cos(phi), std::sin(phi), alpha);
        const double VoH = v.x * h.x + v.z * h.z;
        const glm::dvec3 l = 2.0 * VoH * glm::dvec3(h.x, h.y, h.z) - v;
        if (l.z <= 0.0 || VoH <= 0.0) continue;
        sum += double(V_SmithGGXCorrelated(NoV, float(l.z), alpha)) * VoH * l.z / h.z * l;
    }
    return glm::normalize(sum);
}

// specularLobeMeanLerp's fit against the mean it was fitted to, on a grid off the fit's own: the
// angle between the two in units of the lobe's width (alpha radians, at least 0.02), and t's error. Bounds:
// the fit's measured worst with margin (printed).
TEST(DominantDirection, FollowsTheLobesMeanDirection) {
    const glm::vec3 N(0, 0, 1);
    double worstWidths = 0.0, sumWidths = 0.0;
    int count = 0;
    for (int i = 0; i < 12; ++i)
        for (int j = 0; j < 12; ++j) {
            const float NoV = (float(i) + 0.25f) / 12.0f, perceptualRoughness = (float(j) + 0.75f) / 12.0f;
            const float alpha = perceptualRoughness * perceptualRoughness;
            const glm::vec3 V(std::sqrt(1.0f - NoV * NoV), 0.0f, NoV), R = 2.0f * NoV * N - V;
            const glm::dvec3 mean = lobeMeanDirection(NoV, alpha);
            const glm::dvec3 fitted =
                glm::normalize(glm::dvec3(glm::mix(N, R, specularLobeMeanLerp(NoV, perceptualRoughness))));
            const double angle = std::acos(std::clamp(glm::dot(mean, fitted), -1.0, 1.0));
            const double widths = angle / std::max(double(alpha), 0.02);
            worstWidths = std::max(worstWidths, widths);
            sumWidths += widths;
            ++count;
        }
    std::printf("fitted vs mean direction: worst %.3f, mean %.4f lobe widths\n", worstWidths,
                sumWidths / count);
    EXPECT_LT(worstWidths, 0.5);
    EXPECT_LT(sumWidths / count, 0.04);
    // Listing 22 as printed: smoothness = 1 - alpha, lerp factor smoothness (sqrt(smoothness) + alpha).
    const float alpha = 0.36f, smoothness = 1 - alpha;
    EXPECT_FLOAT_EQ(specularDominantLerpListing22(alpha), smoothness * (std::sqrt(smoothness) + alpha));
    // The direction read: halfway between the two lerp factors; a mirror reads R, a fully rough lobe N; unit
    // length; a degenerate R falls back to N.
    const glm::vec3 R = glm::normalize(glm::vec3(1, 0, 1));
    const float t = 0.5f * (specularDominantLerpListing22(0.25f) + specularLobeMeanLerp(R.z, 0.5f));
    EXPECT_LT(glm::length(glm::vec3(specularDominantDirection(N, R, R.z, 0.5f)) -
                          glm::normalize(glm::mix(N, R, t))),
              1e-6f);
    EXPECT_LT(glm::length(glm::vec3(specularDominantDirection(N, R, R.z, 0.0f)) - R), 1e-6f);
    EXPECT_LT(glm::length(glm::vec3(specularDominantDirection(N, R, R.z, 1.0f)) - N), 1e-6f);
    EXPECT_NEAR(glm::length(glm::vec3(specularDominantDirection(N, R, R.z, 0.5f))), 1.0f, 1e-6f);
    EXPECT_EQ(glm::vec3(specularDominantDirection(N, -N, 0.0f, 1.0f)), N);
}

TEST(Listings, DiffuseDominantDirectionAndOcclusionAsPrinted) {
    glm::vec3 N(0, 0, 1), R = glm::normalize(glm::vec3(1, 0, 1));
    float alpha = 0.36f;
    // Listing 23.
    glm::vec3 V = glm::normalize(glm::vec3(-0.5f, 0, 1));
    float NoV = glm::dot(N, V);
    float a = 1.02341f * alpha - 1.51174f, b = -0.511705f * alpha + 0.755868f;
    float lf = std::clamp((NoV * a + b) * alpha, 0.0f, 1.0f);
    EXPECT_FLOAT_EQ(getDiffuseDominantDir(N, V, NoV, alpha).x, V.x * lf);
    // Listing 26: ao unchanged at alpha = 1 ... (pow(NoV + ao, 2^-17) - 1 + ao ~ ao)
    EXPECT_NEAR(computeSpecOcclusion(0.7f, 0.5f, 1.0f), 0.5f, 1e-5f);
    EXPECT_FLOAT_EQ(computeSpecOcclusion(0.7f, 0.5f, 0.1f),
                    std::clamp(std::pow(1.2f, std::exp2(-2.6f)) - 0.5f, 0.f, 1.f));
    EXPECT_EQ(computeSpecOcclusion(0.3f, 1.0f, 0.2f), 1.0f); // ao = 1: no occlusion
    // Filament 5.6.2.1.
    EXPECT_EQ(horizonOcclusion(R, N), 1.0f);
    EXPECT_FLOAT_EQ(horizonOcclusion(glm::normalize(glm::vec3(1, 0, -1)), N),
                    std::pow(1 - std::sqrt(0.5f), 2.0f));
}

TEST(Listings, SunRepresentativePointIsListing6) {
    SunDisk sun{};
    sun.direction = glm::normalize(glm::vec3(0.2f, 1.0f, 0.1f));
    sun.angularRadius = 0.05f;
    // Inside the disk: R itself.
    glm::vec3 inside = glm::normalize(sun.direction + glm::vec3(0.01f, 0, 0));
    EXPECT_EQ(sunSpecularDirection(sun, inside), inside);
    // Outside: on the disk's rim, in the plane of D and R.
    glm::vec3 R = glm::normalize(glm::vec3(1, 0.3f, 0));
    glm::vec3 L = sunSpecularDirection(sun, R);
    EXPECT_NEAR(glm::dot(L, sun.direction), std::cos(0.05f) / std::sqrt(1.0f), 1e-5f);
    EXPECT_NEAR(glm::dot(glm::cross(sun.direction, R), L), 0.0f, 1e-6f);
    // R opposite to D: any rim point, finite.
    glm::vec3 opposite = sunSpecularDirection(sun, -sun.direction);
    EXPECT_TRUE(std::isfinite(opposite.x + opposite.y + opposite.z));
    EXPECT_NEAR(glm::length(opposite), 1.0f, 1e-5f);
}

// ------------------------------------------------------------------------------------------------
// Geometry

TEST(Parallax, BoxAndSphereIntersectionsAndParallelRays) {
    ProbeVolume box = boxVolume(glm::vec3(1, 2, 3), glm::vec3(2, 1, 4));
    // From the centre along +X: far hit at x = 3, 2 m away.
    ParallaxHit h = parallaxCorrect(box, glm::vec3(0), glm::vec3(1, 2, 3), glm::vec3(1, 0, 0));
    ASSERT_TRUE(h.hit);
    EXPECT_FLOAT_EQ(h.distanceToHit, 2.0f);
    EXPECT_FLOAT_EQ(h.distanceFromCapture, 2.0f);
    // Rays parallel to two faces, the point on a face plane, and exactly on an edge and a corner.
    for (glm::vec3 p : {glm::vec3(1, 2, 3), glm::vec3(1, 3, 3), glm::vec3(3, 3, 7), glm::vec3(-1, 1, -1)})
        for (glm::vec3 d :
             {glm::vec3(1, 0, 0), glm::vec3(0, -1, 0), glm::vec3(0, 0, 1), glm::vec3(-1, 0, 0)}) {
            ParallaxHit q = parallaxCorrect(box, glm::vec3(0.5f, 0, 0), p, d);
            EXPECT_TRUE(std::isfinite(q.distanceToHit) && std::isfinite(q.distanceFromCapture));
            EXPECT_TRUE(std::isfinite(q.direction.x + q.direction.y + q.direction.z));
            EXPECT_NEAR(glm::length(q.direction), 1.0f, 1e-5f);
            if (q.hit) {
                EXPECT_LE(q.distanceToHit, 16.0f);
            }
        }
    // Sphere: far intersection from an off-centre point.
    ProbeVolume sphere = sphereVolume(glm::vec3(0), 2.0f);
    ParallaxHit s = parallaxCorrect(sphere, glm::vec3(0), glm::vec3(1, 0, 0), glm::vec3(-1, 0, 0));
    ASSERT_TRUE(s.hit);
    EXPECT_FLOAT_EQ(s.distanceToHit, 3.0f);
    // Outside and pointing away: no hit.
    EXPECT_FALSE(parallaxCorrect(sphere, glm::vec3(0), glm::vec3(5, 0, 0), glm::vec3(1, 0, 0)).hit);
    EXPECT_FALSE(parallaxCorrect(box, glm::vec3(0), glm::vec3(10, 2, 3), glm::vec3(0, 1, 0)).hit);
}

TEST(Influence, ZeroOutsideOneInsideFadeBetween) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    glm::mat3 rot = glm::mat3(glm::rotate(glm::mat4(1.0f), 0.6f, glm::normalize(glm::vec3(1, 2, 0.5f))));
    ProbeVolume volumes[] = {boxVolume(glm::vec3(1, 0, -2), glm::vec3(3, 1.5f, 2), rot),
                             sphereVolume(glm::vec3(-1, 2, 0), 2.5f, rot)};
    for (const ProbeVolume& v : volumes)
        for (float fade : {0.0f, 0.5f}) {
            int outside = 0, inside = 0;
            for (int i = 0; i < 20000; ++i) {
                glm::vec3 local(4.0f * u(rng), 4.0f * u(rng), 4.0f * u(rng));
                glm::vec3 p = v.center + rot * local;
                bool isInside = v.shape == IBL_VOLUME_BOX
                                    ? (std::abs(local.x) < v.extent.x && std::abs(local.y) < v.extent.y &&
                                       std::abs(local.z) < v.extent.z)
                                    : glm::length(local) < v.extent.x;
                float w = influenceWeight(v, fade, p);
                ASSERT_TRUE(w >= 0.0f && w <= 1.0f);
                if (!isInside) {
                    ASSERT_EQ(w, 0.0f) << "outside point with weight";
                    ++outside;
                } else {
                    ++inside;
                    // Deeper inside than the fade distance (and the 1e-4 floor): full weight.
                    bool deep = v.shape == IBL_VOLUME_BOX ? (std::abs(local.x) < v.extent.x - fade - 1e-3f &&
                                                             std::abs(local.y) < v.extent.y - fade - 1e-3f &&
                                                             std::abs(local.z) < v.extent.z - fade - 1e-3f)
                                                          : glm::length(local) < v.extent.x - fade - 1e-3f;
                    if (deep) {
                        ASSERT_EQ(w, 1.0f);
                    }
                }
            }
            EXPECT_GT(outside, 1000);
            EXPECT_GT(inside, 1000);
        }
    // On the boundary: 0.
    EXPECT_EQ(influenceWeight(boxVolume(glm::vec3(0), glm::vec3(1)), 0.2f, glm::vec3(1, 0, 0)), 0.0f);
    EXPECT_EQ(influenceWeight(sphereVolume(glm::vec3(0), 1.0f), 0.0f, glm::vec3(0, 1, 0)), 0.0f);
    // Zero-size and invalid volumes: 0 everywhere, also at their centre.
    EXPECT_EQ(influenceWeight(boxVolume(glm::vec3(0), glm::vec3(1, 0, 1)), 0.0f, glm::vec3(0)), 0.0f);
    EXPECT_EQ(influenceWeight(sphereVolume(glm::vec3(0), 0.0f), 0.0f, glm::vec3(0)), 0.0f);
    EXPECT_EQ(influenceWeight(sphereVolume(glm::vec3(0), NAN), 0.0f, glm::vec3(0)), 0.0f);
}

// ------------------------------------------------------------------------------------------------
// White furnace

TEST(Furnace, MetalF0OneWithin2PercentForEveryRoughness) {
    const float L = 0.75f;
    CubeMap constant = makeCube(32, [&](glm::vec3) { return glm::vec3(L); });
    ProbeSet set = distantSet(constant);
    std::vector<ShadingPoint> points;
    for (int k = 0; k <= 20; ++k)
        for (float NoV : {0.0f, 0.02f, 0.1f, 0.3f, 0.5f, 0.7f, 0.9f, 1.0f}) {
            glm::vec3 view(std::sqrt(1 - NoV * NoV), 0, NoV);
            points.push_back(
                makeShadingPoint(glm::vec3(0), glm::vec3(0, 0, 1), view, glm::vec3(1), 1.0f, k / 20.0f));
        }
    RuntimeOptions on;
    std::vector<glm::vec4> out = evaluateCpu(set, points, on);
    RuntimeOptions off = on;
    off.energyCompensation = false;
    std::vector<glm::vec4> without = evaluateCpu(set, points, off);
    double worst = 0.0, worstOff = 0.0;
    for (std::size_t i = 0; i < points.size(); ++i) {
        for (int c = 0; c < 3; ++c) {
            double e = std::abs(out[i][c] - L) / L;
            worst = std::max(worst, e);
            worstOff = std::max(worstOff, double(std::abs(without[i][c] - L) / L));
            EXPECT_LT(e, 0.02) << "r=" << points[i].perceptualRoughness << " view=" << points[i].view.z;
        }
    }
    std::printf("white furnace, f0 = 1: max deviation %.5f with energy compensation, %.4f without\n", worst,
                worstOff);
    EXPECT_GT(worstOff, 0.1); // the compensation matters: single scattering loses > 10% at r = 1
    EXPECT_BACKENDS_AGREE(set, points, on);

    // Dielectric white furnace (Lambert + f0 = 0.04): diffuse and specular are added, energy is not
    // conserved by the model (the runtime reproduces the model, not 1): check against the reference.
}

// ------------------------------------------------------------------------------------------------
// Analytic rooms: a mirror at many positions reflects exactly the wall its ray hits.

struct Room {
    ProbeVolume proxy;
    glm::vec3 captureOffset;
    glm::vec3 capturePoint() const {
        return glm::vec3(proxy.center) + glm::vec3(proxy.axisX) * captureOffset.x +
               glm::vec3(proxy.axisY) * captureOffset.y + glm::vec3(proxy.axisZ) * captureOffset.z;
    }
    // Wall seen from the capture point in world direction d.
    int wallSeenFromCapture(glm::vec3 d) const {
        return wallOf(proxy, analyticHitLocal(proxy, capturePoint(), d));
    }
    CubeMap capture(int n) const {
        return makeCube(n, [&](glm::vec3 d) { return kWallColors[wallSeenFromCapture(d)]; });
    }
};

// The four level-0 texels a bilinear lookup in direction d reads (through the border), by wall seen.
bool bilinearTapsSeeOneWall(const Room& room, int n, glm::vec3 d, int wall) {
    CubeCoord c = cubeCoordFromDirection(d);
    float x = c.s * n - 0.5f, y = c.t * n - 0.5f;
    int x0 = int(std::floor(x)), y0 = int(std::floor(y));
    for (int j = 0; j < 2; ++j)
        for (int i = 0; i < 2; ++i) {
            glm::vec3 tap = cubeFaceDirection(c.face, (x0 + i + 0.5f) / n, (y0 + j + 0.5f) / n);
            if (room.wallSeenFromCapture(glm::normalize(tap)) != wall) return false;
        }
    return true;
}

void mirrorRoomTest(const Room& room, const char* name) {
    const int n = 64;
    CubeMap captured = room.capture(n);
    // Distant probe: a colour no wall has, to catch any leak.
    CubeMap outside = makeCube(8, [](glm::vec3) { return glm::vec3(0.0f, 0.0f, 5.0f); });
    ProbeSet set(ldPyramidFromChain(CubeMapChain{{outside}}), dfgTableFromImage(dfgLut()), ShCoefficients{});
    LocalProbeDesc desc;
    desc.proxy = room.proxy;
    desc.captureOffset = room.captureOffset;
    desc.fadeDistance = 0.25f;
    set.addLocalProbe(desc, bakeLd(captured));

    std::mt19937 rng(11);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    std::vector<ShadingPoint> points;
    std::vector<int> walls;
    std::vector<glm::vec3> lookups;
    while (points.size() < 4000) {
        glm::vec3 local(u(rng), u(rng), u(rng));
        if (room.proxy.shape == IBL_VOLUME_BOX) {
            local *= glm::vec3(room.proxy.extent) - glm::vec3(0.3f);
        } else {
            local *= room.proxy.extent.x;
            if (glm::length(local) > room.proxy.extent.x - 0.3f) continue;
        }
        glm::vec3 p = glm::vec3(room.proxy.center) + glm::vec3(room.proxy.axisX) * local.x +
                      glm::vec3(room.proxy.axisY) * local.y + glm::vec3(room.proxy.axisZ) * local.z;
        glm::vec3 nrm = glm::normalize(glm::vec3(u(rng), u(rng), u(rng)));
        glm::vec3 view = glm::normalize(glm::vec3(u(rng), u(rng), u(rng)));
        if (glm::dot(nrm, view) < 0.05f) continue;
        glm::vec3 R = glm::reflect(-view, nrm);
        glm::vec3 hitLocal = analyticHitLocal(room.proxy, p, R);
        glm::vec3 hitWorld = glm::vec3(room.proxy.center) + glm::vec3(room.proxy.axisX) * hitLocal.x +
                             glm::vec3(room.proxy.axisY) * hitLocal.y +
                             glm::vec3(room.proxy.axisZ) * hitLocal.z;
        points.push_back(makeShadingPoint(p, nrm, view, glm::vec3(1.0f), 1.0f, 0.0f));
        walls.push_back(wallOf(room.proxy, hitLocal));
        lookups.push_back(glm::normalize(hitWorld - room.capturePoint()));
    }
    RuntimeOptions options;
    std::vector<glm::vec4> out = evaluateCpu(set, points, options);
    int checked = 0;
    double worst = 0.0;
    for (std::size_t i = 0; i < points.size(); ++i) {
        ASSERT_EQ(out[i].w, 1.0f) << "inside the influence by more than the fade: full local weight";
        if (!bilinearTapsSeeOneWall(room, n, lookups[i], walls[i])) continue; // at a wall's edge
        ++checked;
        glm::vec3 expected = kWallColors[walls[i]];
        for (int c = 0; c < 3; ++c) {
            double e = std::abs(out[i][c] - expected[c]) / expected[c];
            worst = std::max(worst, e);
            ASSERT_LT(e, 1e-4) << name << " point " << i << " wall " << walls[i];
        }
    }
    std::printf("%s: %d of %zu mirror points away from wall edges, max relative error %.2g\n", name, checked,
                points.size(), worst);
    EXPECT_GT(checked, int(0.8 * points.size()));
    EXPECT_BACKENDS_AGREE(set, points, options);
}

TEST(Rooms, BoxProxyMirrorReflectsTheWallItsRayHits) {
    glm::mat3 rot = glm::mat3(glm::rotate(glm::mat4(1.0f), 0.5f, glm::vec3(0, 1, 0)));
    mirrorRoomTest(
        {boxVolume(glm::vec3(1, 1.5f, -2), glm::vec3(4, 1.5f, 3), rot), glm::vec3(1.2f, -0.6f, 0.9f)},
        "box room, rotated, capture offset");
    mirrorRoomTest({boxVolume(glm::vec3(0), glm::vec3(2, 2, 2)), glm::vec3(0)}, "box room, centred capture");
}

TEST(Rooms, SphereProxyMirrorReflectsTheWallItsRayHits) {
    mirrorRoomTest({sphereVolume(glm::vec3(0.5f, 1, -0.3f), 3.0f), glm::vec3(0.8f, -0.4f, 0.5f)},
                   "sphere room, capture offset");
}

// ------------------------------------------------------------------------------------------------
// Composition (Frostbite 4.9.5)

CubeMap constantCube(glm::vec3 c) {
    return makeCube(4, [&](glm::vec3) { return c; });
}

TEST(Composition, NestedProbesFollowTheAlphaRule) {
    const glm::vec3 red(1, 0, 0), green(0, 1, 0), blue(0, 0, 1);
    LocalProbeDesc small, big;
    small.proxy = boxVolume(glm::vec3(0), glm::vec3(1));
    small.fadeDistance = 0.5f;
    big.proxy = sphereVolume(glm::vec3(0.5f, 0, 0), 3.0f);
    big.fadeDistance = 1.0f;
    auto makeSet = [&](bool bigFirst) {
        ProbeSet set(ldPyramidFromChain(CubeMapChain{{constantCube(blue)}}), dfgTableFromImage(dfgLut()),
                     ShCoefficients{});
        if (bigFirst) set.addLocalProbe(big, ldPyramidFromChain(CubeMapChain{{constantCube(green)}}));
        set.addLocalProbe(small, ldPyramidFromChain(CubeMapChain{{constantCube(red)}}));
        if (!bigFirst) set.addLocalProbe(big, ldPyramidFromChain(CubeMapChain{{constantCube(green)}}));
        return set;
    };
    ProbeSet a = makeSet(true), b = makeSet(false);
    ASSERT_EQ(a.localProbes()[0].proxy.shape, IBL_VOLUME_BOX) << "smallest influence first";
    std::vector<ShadingPoint> points;
    for (float x = -3.0f; x <= 4.0f; x += 0.05f)
        points.push_back(makeShadingPoint(glm::vec3(x, 0.2f, 0.1f), glm::vec3(0, 0, 1), glm::vec3(0, 0, 1),
                                          glm::vec3(1), 1.0f, 0.0f));
    RuntimeOptions options;
    options.diffuse = false;
    std::vector<glm::vec4> outA = evaluateCpu(a, points, options), outB = evaluateCpu(b, points, options);
    for (std::size_t i = 0; i < points.size(); ++i) {
        float wSmall = influenceWeight(small.proxy, small.fadeDistance, points[i].position);
        float wBig = influenceWeight(big.proxy, big.fadeDistance, points[i].position);
        float aSmall = wSmall, aBig = std::clamp(wBig - aSmall, 0.0f, 1.0f);
        float alpha = std::clamp(aSmall + aBig, 0.0f, 1.0f);
        glm::vec3 expected = red * aSmall + green * aBig + blue * (1 - alpha);
        for (int c = 0; c < 3; ++c)
            EXPECT_NEAR(outA[i][c], expected[c], 2e-6f) << points[i].position.x;
        EXPECT_NEAR(outA[i].w, alpha, 1e-6f);
        EXPECT_EQ(outA[i], outB[i]) << "order of addition does not matter";
    }
    EXPECT_BACKENDS_AGREE(a, points, options);
}

// ------------------------------------------------------------------------------------------------
// Degenerate inputs: everything finite.

TEST(Degenerate, EveryCaseFinite) {
    CubeMap sky = makeCube(16, skyLike);
    ProbeSet set = distantSet(sky);
    SunDisk sun{};
    sun.direction = glm::normalize(glm::vec3(0.3f, 0.8f, 0.2f));
    sun.angularRadius = 0.0047f;
    sun.color = glm::vec3(1.0f, 0.95f, 0.9f);
    sun.illuminance = 1e5f;
    set.setSun(sun);
    LdPyramid local = bakeLd(makeCube(16, [](glm::vec3 d) { return glm::abs(d); }));
    LocalProbeDesc box;
    box.proxy = boxVolume(glm::vec3(0), glm::vec3(2, 1, 3));
    box.captureOffset = glm::vec3(0.5f, 0.2f, -0.4f);
    box.fadeDistance = 0.3f;
    set.addLocalProbe(box, local);
    LocalProbeDesc sphere;
    sphere.proxy = sphereVolume(glm::vec3(1, 0, 0), 1.5f);
    sphere.captureOffset = glm::vec3(0.3f, 0, 0);
    set.addLocalProbe(sphere, local);
    // Zero-size proxies and influences: weight 0.
    LocalProbeDesc zeroBox;
    zeroBox.proxy = boxVolume(glm::vec3(0), glm::vec3(0));
    set.addLocalProbe(zeroBox, local);
    LocalProbeDesc zeroSphere;
    zeroSphere.proxy = sphereVolume(glm::vec3(0.1f), 0.0f);
    set.addLocalProbe(zeroSphere, local);
    LocalProbeDesc zeroInfluence = box;
    zeroInfluence.influence = boxVolume(glm::vec3(0), glm::vec3(1, 0, 1));
    set.addLocalProbe(zeroInfluence, local);
    // A capture point on the proxy's boundary (localR can vanish).
    LocalProbeDesc onWall = box;
    onWall.captureOffset = glm::vec3(2, 0, 0);
    set.addLocalProbe(onWall, local);

    std::vector<glm::vec3> positions = {glm::vec3(0),
                                        glm::vec3(2, 0, 0),
                                        glm::vec3(2, 1, 3),
                                        glm::vec3(-2, -1, -3),
                                        glm::vec3(0.5f, 0.2f, -0.4f),
                                        glm::vec3(2.5f, 0, 0),
                                        glm::vec3(100, 0, 0),
                                        glm::vec3(0.1f),
                                        glm::vec3(1, 0, 1.5f)};
    std::vector<glm::vec3> dirs = {glm::vec3(1, 0, 0),
                                   glm::vec3(0, 1, 0),
                                   glm::vec3(0, 0, -1),
                                   glm::vec3(-1, 0, 0),
                                   glm::vec3(0),
                                   glm::vec3(1, 1, 0),
                                   glm::normalize(glm::vec3(0.3f, 0.8f, 0.2f)),
                                   -glm::normalize(glm::vec3(0.3f, 0.8f, 0.2f))};
    std::vector<ShadingPoint> points;
    for (glm::vec3 p : positions)
        for (glm::vec3 n : dirs)
            for (glm::vec3 v : dirs)
                for (float r : {-0.5f, 0.0f, 1e-4f, 0.5f, 1.0f, 3.0f})
                    for (float m : {0.0f, 1.0f})
                        points.push_back(makeShadingPoint(p, n, v, glm::vec3(0.8f), m, r, 0.5f));
    // NoV = 0 exactly: view perpendicular to the normal.
    points.push_back(
        makeShadingPoint(glm::vec3(0), glm::vec3(0, 1, 0), glm::vec3(1, 0, 0), glm::vec3(1), 1, 0));
    points.push_back(
        makeShadingPoint(glm::vec3(0), glm::vec3(0, 1, 0), glm::vec3(1, 0, 0), glm::vec3(1), 0, 1));
    for (const RuntimeOptions& options : {RuntimeOptions{}, RuntimeOptions{.energyCompensation = true,
                                                            .diffuseModel = DiffuseModel::Disney,
                                                            .diffuseDominantDirection = true,
                                                            .f90FromF0 = true}}) {
        std::vector<ShadeResult> out = shadeCpu(set, points, options);
        for (std::size_t i = 0; i < out.size(); ++i) {
            const ShadeResult& s = out[i];
            for (float x : {s.diffuse.x, s.diffuse.y, s.diffuse.z, s.specular.x, s.specular.y, s.specular.z,
                            s.localAlpha}) {
                ASSERT_TRUE(std::isfinite(x)) << "point " << i;
                ASSERT_GE(x, 0.0f) << "point " << i;
            }
            ASSERT_LE(s.localAlpha, 1.0f);
        }
        EXPECT_BACKENDS_AGREE(set, points, options);
    }
    // Zero-size probes change nothing: same result as a set without them.
    ProbeSet plain = distantSet(sky);
    plain.setSun(sun);
    ProbeSet zeros = distantSet(sky);
    zeros.setSun(sun);
    zeros.addLocalProbe(zeroBox, local);
    zeros.addLocalProbe(zeroSphere, local);
    zeros.addLocalProbe(zeroInfluence, local);
    std::vector<glm::vec4> a = evaluateCpu(plain, points), b = evaluateCpu(zeros, points);
    for (std::size_t i = 0; i < points.size(); ++i)
        ASSERT_EQ(a[i], b[i]);
}

// ------------------------------------------------------------------------------------------------
// Loading

TEST(Loading, Ktx2ChainAndLutRoundTrip) {
    namespace fs = std::filesystem;
    fs::path dir = fs::temp_directory_path() / ("iblbake_runtime_test_" + std::to_string(::getpid()));
    fs::create_directories(dir);
    CubeMap sky = makeCube(16, skyLike);
    CubeMapChain chain = bakeSpecular(sky, SpecularSettings{}, Executor::cpu());
    writeKtx2Cube(dir / "ld.ktx2", chain, Ktx2Format::RGBA32F,
                  {{"iblbake.roughnessMapping", "linear: level m of L holds perceptualRoughness m/(L-1)"}});
    writeKtx2Image(dir / "dfg.ktx2", dfgLut(), Ktx2Format::RGBA32F, {});
    LdPyramid loaded = loadLdKtx2(dir / "ld.ktx2");
    LdPyramid direct = ldPyramidFromChain(chain, MipMapping::Linear);
    EXPECT_EQ(loaded.mapping, MipMapping::Linear);
    EXPECT_EQ(loaded.layout.levelCount, direct.layout.levelCount);
    EXPECT_EQ(loaded.data, direct.data);
    DfgTable lut = loadDfgKtx2(dir / "dfg.ktx2");
    EXPECT_EQ(lut.data, dfgTableFromImage(dfgLut()).data);
    // Half floats load too (rounded); a LUT is not a cube and a cube is not a LUT.
    writeKtx2Cube(dir / "ld16.ktx2", chain, Ktx2Format::RGBA16F, {});
    EXPECT_EQ(loadLdKtx2(dir / "ld16.ktx2").mapping, MipMapping::Frostbite);
    EXPECT_THROW(loadLdKtx2(dir / "dfg.ktx2"), Error);
    EXPECT_THROW(loadDfgKtx2(dir / "ld.ktx2"), Error);
    EXPECT_THROW(parseStoredMipMapping("cubic"), Error);
    // A chain whose levels do not halve is refused.
    CubeMapChain bad = chain;
    bad.levels[1] = CubeMap(16);
    EXPECT_THROW(ldPyramidFromChain(bad), Error);
    fs::remove_all(dir);
}

// ------------------------------------------------------------------------------------------------
// Throughput and OpenCL vs CPU on a full scene.

TEST(Throughput, CpuAndOpenCL) {
    CubeMap sky = makeCube(64, skyLike);
    ProbeSet set = distantSet(sky);
    // Sun to sky illuminance about 20 (a clear day: ~100 klux of sun, 5-20 klux of sky). With 1e5 times the
    // sky, a sun grazing the surface (N.D ~ 1e-5) makes the result ill-conditioned: fp32 rounding of N.D
    // alone then moves it by ~0.5% between the compilers.
    SunDisk sun{glm::normalize(glm::vec3(0.5f, 0.4f, 0.6f)), 0.0047f, glm::vec3(1), 30.0f};
    set.setSun(sun);
    LocalProbeDesc box;
    box.proxy = boxVolume(glm::vec3(0), glm::vec3(4, 2, 4),
                          glm::mat3(glm::rotate(glm::mat4(1.0f), 0.3f, glm::vec3(0, 1, 0))));
    box.captureOffset = glm::vec3(0.5f, -0.5f, 0.2f);
    box.fadeDistance = 0.5f;
    set.addLocalProbe(box, bakeLd(makeCube(64, [](glm::vec3 d) { return 0.5f * (d + 1.0f); })));
    LocalProbeDesc sphere;
    sphere.proxy = sphereVolume(glm::vec3(2, 0, 0), 2.0f);
    sphere.fadeDistance = 0.5f;
    set.addLocalProbe(sphere, bakeLd(makeCube(32, skyLike)));

    std::mt19937 rng(3);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f), u01(0.0f, 1.0f);
    const std::size_t count = 1 << 20;
    std::vector<ShadingPoint> points(count);
    for (ShadingPoint& p : points) {
        glm::vec3 n = glm::normalize(glm::vec3(u(rng), u(rng), u(rng)) + glm::vec3(0, 1e-3f, 0));
        glm::vec3 v = glm::normalize(n + glm::vec3(u(rng), u(rng), u(rng)));
        p = makeShadingPoint(glm::vec3(5 * u(rng), 2.5f * u(rng), 5 * u(rng)), n, v,
                             glm::vec3(u01(rng), u01(rng), u01(rng)), u01(rng) < 0.5f ? 0.0f : 1.0f, u01(rng),
                             u01(rng));
    }
    RuntimeOptions options;
    evaluateCpu(set, std::span(points).first(1024), options); // warm up
    auto start = std::chrono::steady_clock::now();
    std::vector<glm::vec4> cpu = evaluateCpu(set, points, options);
    double cpuMs =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    std::printf("CPU (TBB, %d local probes + sun): %zu points in %.1f ms = %.2f Mpoints/s\n",
                int(set.localProbes().size()), count, cpuMs, count / cpuMs / 1e3);
    Executor executor = openclOrCpu();
    if (!executor.usesOpenCL()) GTEST_SKIP() << "no OpenCL device";
    OpenCLProbeEvaluator cl(executor.cl(), set);
    cl.evaluate(std::span(points).first(1024), options); // program build
    start = std::chrono::steady_clock::now();
    std::vector<glm::vec4> gpu = cl.evaluate(points, options);
    double clMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    std::printf("OpenCL (%s): %zu points in %.1f ms (kernel %.1f ms) = %.2f Mpoints/s\n",
                executor.description().c_str(), count, clMs, cl.lastKernelMilliseconds(), count / clMs / 1e3);
    double worst = 0.0;
    for (std::size_t i = 0; i < count; ++i)
        worst = std::max(worst, relativeDifference(gpu[i], cpu[i], 1e-3f));
    std::printf("OpenCL vs CPU over %zu random points: max relative difference %.3g\n", count, worst);
    EXPECT_LT(worst, kBackendTolerance);
}

} // namespace
