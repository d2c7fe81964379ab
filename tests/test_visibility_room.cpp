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

const ProbeVolume& kRoom = kWindowRoom;
const glm::vec3 kOffset(0.0f, 0.2f, 0.0f);
const glm::vec3& kCapturePoint = kWindowRoomCapturePoint;
// Toward the window's centre as a floor point 0.66 m from the room's centre reflects it to the camera below.
const glm::vec3 kSunDirection = glm::normalize(glm::vec3(1.0f, 0.64f, 0.05f));

// The distant map: a sky gradient and a sun disc (3 degrees, 50 times the sky) that the window frames.
constexpr float kSunAngularRadius = 0.05f;
const glm::vec3 kSunRadiance(50.0f, 45.0f, 35.0f);

glm::vec3 sky(glm::vec3 d) {
    return glm::vec3(0.3f, 0.5f, 1.0f) * (0.6f + 0.4f * std::max(d.y, 0.0f)) + glm::vec3(0.2f * d.z);
}

glm::vec3 outside(glm::vec3 d) {
    return glm::dot(d, kSunDirection) > std::cos(kSunAngularRadius) ? kSunRadiance : sky(d);
}

// The same sun taken out of the map as an analytic disk light (iblbake's extractSun): the disk of uniform
// radiance kSunRadiance, whose illuminance is its luminance times its projected solid angle.
SunDisk extractedSun() {
    const float luminance = glm::dot(kSunRadiance, glm::vec3(0.2126f, 0.7152f, 0.0722f));
    const float projectedSolidAngle = 3.14159265f * std::sin(kSunAngularRadius) * std::sin(kSunAngularRadius);
    return SunDisk{kSunDirection, kSunAngularRadius, kSunRadiance / luminance,
                   luminance * projectedSolidAngle};
}

// What the room sees outside its window: the map with its sun, or the sky alone (no sun, or the sun
// extracted as a disk light).
using Outside = glm::vec3 (*)(glm::vec3);

// The capture from the capture point, 2 x 2 sub-texel directions: premultiplied, window texels RGBA 0; or,
// with frozenSky, what a capture without visibility holds (the window shows the outside as seen from the
// capture point, alpha 1).
CubeMap roomCapture(int n, bool frozenSky = false, Outside outsideMap = outside) {
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
                            sum += glm::vec4(outsideMap(d), 1.0f);
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
RoomSet roomSet(int captureSize, bool frozenSky = false, Outside outsideMap = outside) {
    CubeMap capture = roomCapture(captureSize, frozenSky, outsideMap), distant = makeCube(64, outsideMap, 2);
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

TEST(VisibilityRoomEndToEnd, MirrorsThroughTheWindowGetTheDistantMapAndTheOthersTheWall) {
    const int n = 128;
    RoomSet room = roomSet(n);
    ReferenceLighting far = ReferenceLighting::distant(room.distant);
    const RoomMirrorPoints mirrors = windowRoomMirrorPoints(6000, 21, n);
    const RoomMirrors m = checkRoomMirrors(
        room.set, RuntimeOptions{}, mirrors,
        [&](const ShadingPoint& p, glm::vec3 R) {
            return glm::vec3(far.radiance(p.position, glm::dvec3(R)));
        },
        "room");
    EXPECT_GT(m.throughWindow, 300);
    EXPECT_GT(m.onWall, 2000);
    RuntimeOptions specularOnly;
    specularOnly.diffuse = false;
    EXPECT_BACKENDS_AGREE(room.set, mirrors.points, specularOnly);
}

// A glossy metal floor whose reflections run up the window wall, against the reference of the same room
// (the capture projected onto the proxy, the distant map behind the window), in three configurations of
// the outside:
// - "sky": a sky without a sun; what the composition itself costs next to the local probe's own
//   approximations, which the existing local-probe floor (test_runtime_accuracy DistanceRoughness: 13-39%
//   at r = 0.1-0.4 on striped and checkered walls) measures;
// - "sun extracted": the sun taken out as a disk light, as iblbake bakes a sunny map
// (environment.extractSun);
//   an engine shadows it (its shadow map), here by the fraction of the disk the window shows the point;
// - "sun left in": the sun in the distant map, where the split sum's own error at these grazing views of a
//   compact source dominates (iblbake warns of it: sun_in_probe.h).
// Printed beside each: the probe without visibility (the window's sky frozen in the capture, what a probe
// did before) against the same reference, and the split sum's own error for the distant lighting alone at
// the same points (ReferenceLighting::distant), which bounds what any composition of split-sum probes
// reaches.
struct FloorConfiguration {
    const char* name;
    Outside outsideMap;
    std::optional<SunDisk> sun;
};

// The fraction of the sun's disk that reaches p through the window (the engine's shadow map), on a
// Fibonacci spiral of the disk's directions.
float sunThroughWindow(glm::vec3 p, const SunDisk& sun) {
    const int count = 256;
    const glm::vec3 t = glm::normalize(glm::cross(sun.direction, glm::vec3(0, 0, 1)));
    const glm::vec3 b = glm::cross(sun.direction, t);
    int seen = 0;
    for (int i = 0; i < count; ++i) {
        const float radius = sun.angularRadius * std::sqrt((i + 0.5f) / count), phi = 2.39996323f * i;
        const glm::vec3 d = glm::normalize(sun.direction + radius * (std::cos(phi) * t + std::sin(phi) * b));
        seen += inWindow(analyticHitLocal(kRoom, p, d));
    }
    return float(seen) / count;
}

// The runtime's result with an analytic sun shadowed by `shadow`: the probes' part plus the sun's.
std::vector<glm::vec4> withShadowedSun(std::vector<glm::vec4> probes, std::span<const glm::vec4> sunOnly,
                                       std::span<const float> shadow) {
    for (std::size_t i = 0; i < probes.size(); ++i)
        probes[i] += glm::vec4(glm::vec3(sunOnly[i]) * shadow[i], 0.0f);
    return probes;
}

TEST(VisibilityRoomEndToEnd, GlossyFloorFacingTheWindowAgainstTheReference) {
    const glm::vec3 camera(-2.0f, 1.7f, 0.0f);
    const ReferenceSettings settings{.samplesPerStrategy = 4096};
    RuntimeOptions options;
    options.diffuse = false;
    for (const FloorConfiguration& config : {FloorConfiguration{"sky", sky, std::nullopt},
                                             FloorConfiguration{"sun extracted", sky, extractedSun()},
                                             FloorConfiguration{"sun left in", outside, std::nullopt}}) {
        RoomSet room = roomSet(64, false, config.outsideMap), frozen = roomSet(64, true, config.outsideMap);
        ReferenceLighting lighting = ReferenceLighting::projectedWithVisibility(room.capture, kRoom, kOffset,
                                                                                room.distant, config.sun);
        ReferenceLighting far = ReferenceLighting::distant(room.distant, config.sun);
        ProbeSet distantOnly(bakeLd(room.distant), dfgTableFromImage(dfgLut()), ShCoefficients{});
        ProbeSet sunOnly(bakeLd(makeCube(8, [](glm::vec3) { return glm::vec3(0.0f); })),
                         dfgTableFromImage(dfgLut()), ShCoefficients{});
        if (config.sun) sunOnly.setSun(*config.sun);
        for (float r : {0.3f, 0.6f}) {
            std::vector<ShadingPoint> points;
            std::vector<float> shadow, unshadowed;
            for (float x = 0.0f; x < 2.9f; x += 0.1f)
                for (float z = -1.0f; z <= 1.0f; z += 0.2f) {
                    glm::vec3 p(x, 1e-3f, z);
                    points.push_back(makeShadingPoint(p, glm::vec3(0, 1, 0), glm::normalize(camera - p),
                                                      glm::vec3(1.0f), 1.0f, r));
                    shadow.push_back(config.sun ? sunThroughWindow(p, *config.sun) : 0.0f);
                    unshadowed.push_back(config.sun ? 1.0f : 0.0f);
                }
            const std::vector<glm::vec4> sun = evaluateCpu(sunOnly, points, options);
            const std::vector<ReferenceResult> ref = renderReference(lighting, points, options, settings);
            const std::vector<glm::vec4> out =
                withShadowedSun(evaluateCpu(room.set, points, options), sun, shadow);
            const double e = relativeError(out, ref);
            const double eFrozen =
                relativeError(withShadowedSun(evaluateCpu(frozen.set, points, options), sun, shadow), ref);
            const double eSplitSum =
                relativeError(withShadowedSun(evaluateCpu(distantOnly, points, options), sun, unshadowed),
                              renderReference(far, points, options, settings));
            double alpha = 0.0;
            for (const glm::vec4& v : out)
                alpha += v.w / double(out.size());
            std::printf("glossy metal floor toward the window, %s, r = %.1f: relative error %.1f%% with "
                        "visibility (mean local alpha %.2f), %.1f%% with the frozen sky; the split sum alone "
                        "on the distant lighting %.1f%%\n",
                        config.name, r, 100.0 * e, alpha, 100.0 * eFrozen, 100.0 * eSplitSum);
            EXPECT_LT(alpha, 0.999) << "the window lets the distant probe in";
            if (config.outsideMap == outside) {
                // The capture froze the sun where the capture point saw it, which the proxy moves: the
                // distant probe through the window puts it back where the floor sees it. 0.47: measured
                // 46.0% at r = 0.3 (44.9% while the lookup direction was Listing 22's, nearer R, which suits
                // a sun left in; probe.h's specularDominantDirection says why it is halfway to the mean).
                EXPECT_LT(e, eFrozen) << config.name << ", r = " << r;
                EXPECT_LT(e, 0.47) << config.name << ", r = " << r;
            } else {
                // Within the existing local-probe floor's measured 13-39%; and where the capture froze the
                // very sky the distant probe holds (smooth, so the proxy's re-projection barely moves it),
                // 4.9.5's product of separately filtered visibility and radiance costs little beside it
                // (measured 0.3-1.2 points).
                EXPECT_LT(e, 0.39) << config.name << ", r = " << r;
                EXPECT_LT(e, eFrozen + 0.02) << config.name << ", r = " << r;
            }
            EXPECT_BACKENDS_AGREE(room.set, points, options);
        }
    }
}

} // namespace
