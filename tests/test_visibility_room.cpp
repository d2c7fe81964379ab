// The analytic room of issue 16 end to end: a box proxy with walls of distinct colours and a window whose
// texels have visibility 0, a distant map with a sun outside. The capture is pre-filtered with its visibility
// (bakeSpecularWithVisibility), the runtime composes it with the distant probe (Frostbite 4.9.5), and the
// reference traces the same configuration (the capture projected onto the proxy, the distant map behind
// its transparent part; ReferenceLighting::projectedWithVisibility).
#include "room_test_support.h"
#include "runtime_test_support.h"

#include <iblbake/runtime/runtime_reference.h>

#include <random>

namespace {

using namespace ibl;
using namespace rt_test;

const ProbeVolume kRoom = boxVolume(glm::vec3(0, 1.5f, 0), glm::vec3(3, 1.5f, 3));
const glm::vec3 kOffset(0.0f, 0.2f, 0.0f);
const glm::vec3 kCapturePoint = glm::vec3(kRoom.center) + kOffset;
// Toward the window's centre as a floor point 0.66 m from the room's centre reflects it to the camera below.
const glm::vec3 kSunDirection = glm::normalize(glm::vec3(1.0f, 0.64f, 0.05f));

// The window: part of the +X wall (proxy-local coordinates).
bool inWindow(glm::vec3 local) {
    return local.x > 2.999f && std::abs(local.y) < 0.8f && std::abs(local.z) < 1.2f;
}

// The distant map: a sky gradient and a sun disc (3 degrees, 50 times the sky) that the window frames.
glm::vec3 outside(glm::vec3 d) {
    glm::vec3 sky = glm::vec3(0.3f, 0.5f, 1.0f) * (0.6f + 0.4f * std::max(d.y, 0.0f)) + glm::vec3(0.2f * d.z);
    return glm::dot(d, kSunDirection) > std::cos(0.05f) ? glm::vec3(50.0f, 45.0f, 35.0f) : sky;
}

// The capture from the capture point, 2 x 2 sub-texel directions: premultiplied, window texels RGBA 0; or,
// with frozenSky, what a capture without visibility holds (the window shows the outside as seen from the
// capture point, alpha 1).
CubeMap roomCapture(int n, bool frozenSky = false) {
    CubeMap cube(n);
    for (int f = 0; f < 6; ++f)
        for (int y = 0; y < n; ++y)
            for (int x = 0; x < n; ++x) {
                glm::vec4 sum(0.0f);
                for (int j = 0; j < 2; ++j)
                    for (int i = 0; i < 2; ++i) {
                        glm::vec3 d = glm::normalize(glm::vec3(
                            cubeFaceDirection(f, (x + (i + 0.5f) / 2) / n, (y + (j + 0.5f) / 2) / n)));
                        glm::vec3 hit = analyticHitLocal(kRoom, kCapturePoint, d);
                        if (!inWindow(hit))
                            sum += glm::vec4(kWallColors[wallOf(kRoom, hit)], 1.0f);
                        else if (frozenSky)
                            sum += glm::vec4(outside(d), 1.0f);
                    }
                cube.faces[f].at(x, y) = 0.25f * sum;
            }
    return cube;
}

struct RoomSet {
    CubeMap capture, distant;
    ProbeSet set;
};

// The distant probe and the room's probe (with its visibility, or with the frozen sky and none).
RoomSet roomSet(int captureSize, bool frozenSky = false) {
    CubeMap capture = roomCapture(captureSize, frozenSky), distant = makeCube(64, outside, 2);
    static Executor executor = openclOrCpu();
    VisibilityChain baked = bakeSpecularWithVisibility(capture, SpecularSettings{}, executor);
    EXPECT_EQ(baked.hasVisibility, !frozenSky);
    ProbeSet set(bakeLd(distant), dfgTableFromImage(dfgLut()), ShCoefficients{});
    LocalProbeDesc desc;
    desc.proxy = kRoom;
    desc.captureOffset = kOffset;
    set.addLocalProbe(
        desc, ldPyramidFromChain(baked.chain, MipMapping::Frostbite, ChainAlpha::PremultipliedVisibility));
    return {capture, distant, set};
}

// Whether the four level-0 texels a bilinear lookup in direction d reads are all window or all one wall.
bool tapsAgree(int n, glm::vec3 d, bool window, int wall) {
    CubeCoord c = cubeCoordFromDirection(d);
    float x = c.s * n - 0.5f, y = c.t * n - 0.5f;
    int x0 = int(std::floor(x)), y0 = int(std::floor(y));
    for (int j = -1; j < 3; ++j) // the taps and their neighbours: the capture averages 2 x 2 sub-texels
        for (int i = -1; i < 3; ++i) {
            glm::vec3 tap = glm::normalize(
                glm::vec3(cubeFaceDirection(c.face, (x0 + i + 0.5f) / n, (y0 + j + 0.5f) / n)));
            glm::vec3 hit = analyticHitLocal(kRoom, kCapturePoint, tap);
            if (inWindow(hit) != window || (!window && wallOf(kRoom, hit) != wall)) return false;
        }
    return true;
}

TEST(VisibilityRoomEndToEnd, MirrorsThroughTheWindowGetTheDistantMapAndTheOthersTheWall) {
    const int n = 128;
    RoomSet room = roomSet(n);
    ReferenceLighting far = ReferenceLighting::distant(room.distant);
    std::mt19937 rng(21);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    std::vector<ShadingPoint> points;
    std::vector<int> kind; // -1 not checked, 0..5 wall, 6 window
    while (points.size() < 6000) {
        glm::vec3 p =
            glm::vec3(kRoom.center) + glm::vec3(u(rng), u(rng), u(rng)) * (glm::vec3(kRoom.extent) - 0.3f);
        glm::vec3 nrm = glm::normalize(glm::vec3(u(rng), u(rng), u(rng)));
        // Half of the views chosen so that the mirror looks at the window's side of the room.
        glm::vec3 target = points.size() % 2 ? glm::vec3(3.0f, 1.5f + u(rng), 1.2f * u(rng))
                                             : p + glm::vec3(u(rng), u(rng), u(rng));
        glm::vec3 R = glm::normalize(target - p);
        nrm = glm::normalize(R + glm::normalize(glm::vec3(u(rng), u(rng), u(rng))));
        glm::vec3 view = glm::reflect(-R, nrm);
        if (glm::dot(nrm, view) < 0.05f) continue;
        glm::vec3 hit = analyticHitLocal(kRoom, p, R);
        glm::vec3 lookup = glm::normalize(glm::vec3(kRoom.center) + hit - kCapturePoint);
        bool window = inWindow(hit);
        int wall = wallOf(kRoom, hit);
        points.push_back(makeShadingPoint(p, nrm, view, glm::vec3(1.0f), 1.0f, 0.0f));
        kind.push_back(tapsAgree(n, lookup, window, wall) ? (window ? 6 : wall) : -1);
    }
    RuntimeOptions options;
    options.diffuse = false;
    std::vector<glm::vec4> out = evaluateCpu(room.set, points, options);
    int throughWindow = 0, onWall = 0;
    double worstWindow = 0.0, worstWall = 0.0;
    for (std::size_t i = 0; i < points.size(); ++i) {
        if (kind[i] < 0) continue;
        glm::vec3 R = glm::reflect(-points[i].view, points[i].normal);
        glm::vec3 expected = kind[i] == 6
                                 ? glm::vec3(far.radiance(points[i].position, glm::dvec3(glm::normalize(R))))
                                 : kWallColors[kind[i]];
        double e = 0.0;
        for (int c = 0; c < 3; ++c)
            e = std::max(e, double(std::abs(out[i][c] - expected[c]) / expected[c]));
        if (kind[i] == 6) {
            ++throughWindow;
            worstWindow = std::max(worstWindow, e);
            EXPECT_EQ(out[i].w, 0.0f) << "point " << i << ": the window is transparent";
        } else {
            ++onWall;
            worstWall = std::max(worstWall, e);
        }
        EXPECT_LT(e, 0.01) << "point " << i << (kind[i] == 6 ? " through the window" : " on a wall");
    }
    std::printf(
        "room, mirrors: %d through the window (max relative error to the distant map %.2g), %d on walls "
        "(to the wall %.2g)\n",
        throughWindow, worstWindow, onWall, worstWall);
    EXPECT_GT(throughWindow, 300);
    EXPECT_GT(onWall, 2000);
    EXPECT_BACKENDS_AGREE(room.set, points, options);
}

double relativeError(std::span<const glm::vec4> runtime, std::span<const ReferenceResult> reference) {
    double err = 0.0, sum = 0.0;
    for (std::size_t i = 0; i < runtime.size(); ++i)
        for (int c = 0; c < 3; ++c) {
            err += std::abs(double(runtime[i][c]) - reference[i].total()[c]);
            sum += std::abs(reference[i].total()[c]);
        }
    return err / sum;
}

// A glossy metal floor whose reflections run up the window wall, against the reference of the same room
// (the capture projected onto the proxy, the distant map behind the window). Printed beside it: today's probe
// (the window's frozen sky from the capture point, no visibility) against the same reference, and the split
// sum's own error for the distant map alone at the same points (ReferenceLighting::distant), which bounds
// what any composition of split-sum probes can reach at these grazing views.
TEST(VisibilityRoomEndToEnd, GlossyFloorFacingTheWindowAgainstTheReference) {
    RoomSet room = roomSet(64), frozen = roomSet(64, true);
    ReferenceLighting lighting =
        ReferenceLighting::projectedWithVisibility(room.capture, kRoom, kOffset, room.distant);
    ReferenceLighting far = ReferenceLighting::distant(room.distant);
    ProbeSet distantOnly(bakeLd(room.distant), dfgTableFromImage(dfgLut()), ShCoefficients{});
    const glm::vec3 camera(-2.0f, 1.7f, 0.0f);
    for (float r : {0.3f, 0.6f}) {
        std::vector<ShadingPoint> points;
        for (float x = 0.0f; x < 2.9f; x += 0.1f)
            for (float z = -1.0f; z <= 1.0f; z += 0.2f) {
                glm::vec3 p(x, 1e-3f, z);
                points.push_back(makeShadingPoint(p, glm::vec3(0, 1, 0), glm::normalize(camera - p),
                                                  glm::vec3(1.0f), 1.0f, r));
            }
        RuntimeOptions options;
        options.diffuse = false;
        const ReferenceSettings settings{.samplesPerStrategy = 4096};
        std::vector<ReferenceResult> ref = renderReference(lighting, points, options, settings);
        std::vector<glm::vec4> out = evaluateCpu(room.set, points, options);
        const double e = relativeError(out, ref);
        const double eFrozen = relativeError(evaluateCpu(frozen.set, points, options), ref);
        const double eSplitSum = relativeError(evaluateCpu(distantOnly, points, options),
                                               renderReference(far, points, options, settings));
        double alpha = 0.0;
        for (const glm::vec4& v : out)
            alpha += v.w / double(out.size());
        std::printf(
            "glossy metal floor toward the window, r = %.1f: relative error %.1f%% with visibility (mean "
            "local alpha %.2f), %.1f%% with the frozen sky; the split sum alone on the distant map "
            "%.1f%%\n",
            r, 100.0 * e, alpha, 100.0 * eFrozen, 100.0 * eSplitSum);
        EXPECT_LT(e, eFrozen) << "r = " << r << ": the distant probe through the window beats the frozen sky";
        // The existing local-probe floor (test_runtime_accuracy DistanceRoughness) measures 13-39% at r =
        // 0.1-0.4 with no sun; here the split sum's own error on the sun at these views is most of it.
        EXPECT_LT(e, 0.45) << "r = " << r;
        EXPECT_LT(alpha, 0.999) << "the window lets the distant probe in";
        EXPECT_BACKENDS_AGREE(room.set, points, options);
    }
}

} // namespace
