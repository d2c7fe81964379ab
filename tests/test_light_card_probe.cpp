// Issue 15 item 6, a light card against a probe (Drobot 1.4.1: an image-based light card and a cubemap
// reflection at a distance should swap without visible change): the card's texture placed in an otherwise
// black environment as seen from the shading point, baked in-process as a probe with the production
// specular chain and irradiance cube, against the same card shaded as a textured rectangle light. Both are
// also compared with the fp64 brute force over the textured rectangle, which says which of the two carries
// a difference. Table printed: roughness x distance, diffuse and specular separately.
#include "light_card_test_support.h"
#include "runtime_test_support.h"

#include <cstdio>
#include <string>
#include <vector>

namespace {

using namespace ibl;
using namespace ibl::test;

// The radiance an environment captured at p sees in direction d: the light's emission texel (nearest, as
// the brute force reads it) where the ray meets the rectangle from its emitting side, black elsewhere.
glm::vec3 cardInEnvironment(const AreaLight& light, const ImageRGBA& emission, glm::vec3 p, glm::vec3 d) {
    const glm::vec3 normal = glm::normalize(light.normal), tangent = glm::normalize(light.tangent);
    const glm::vec3 bitangent = glm::cross(normal, tangent);
    const float height = glm::dot(p - light.position, normal), along = -glm::dot(d, normal);
    if (height <= 0.0f || along <= 0.0f) return glm::vec3(0.0f);
    const glm::vec3 fromCenter = p + d * (height / along) - light.position;
    const float u = 0.5f + 0.5f * glm::dot(fromCenter, tangent) / light.halfWidth;
    const float v = 0.5f - 0.5f * glm::dot(fromCenter, bitangent) / light.halfHeight;
    if (u < 0.0f || u >= 1.0f || v < 0.0f || v >= 1.0f) return glm::vec3(0.0f);
    const int x = std::min(int(u * float(emission.width)), emission.width - 1);
    const int y = std::min(int(v * float(emission.height)), emission.height - 1);
    return light.color * light.luminance * glm::vec3(emission.at(x, y));
}

// Mean relative differences (luminance) of one (roughness, distance) cell.
struct CellDifference {
    double diffuse = 0.0, specular = 0.0;                 // probe vs textured light
    double probeDiffuse = 0.0, probeSpecular = 0.0;       // probe vs brute force
    double texturedDiffuse = 0.0, texturedSpecular = 0.0; // textured light vs brute force
};

const float kRoughness[] = {0.1f, 0.3f, 0.6f, 1.0f};
const float kDistance[] = {3.0f, 10.0f, 30.0f}; // light sizes (sqrt of its area)
const float kViewAngle[] = {0.0f, 0.5f};        // radians: 0 and 29 degrees off the mirror
const glm::vec3 kTargets[] = {{0.0f, 0.0f, 0.0f}, {0.3f, -0.2f, 0.0f}}; // the centre, and off it
constexpr float kElevation = 0.5f, kAzimuth = 0.6f;                     // one probe position per distance
constexpr int kCubeSize = 512, kSupersample = 4; // the environment the probe is baked from

// The sweep: one probe per distance (captured at the shading point, 512-px faces), 4 roughnesses x 2 views
// x 2 reflection targets on it. Bounds, the table's measurement with margin (the README's table):
//   diffuse   1.5% from 3 light sizes on (measured 1.0%, 0.3%, 0.4% at 3, 10, 30): the irradiance cube and
//             the card's form factor with its diffuse layer agree.
//   specular  15% where they match: roughness >= 0.6 at every distance, 0.3 from 10 light sizes on
//             (measured 5-12%; the probe's split sum, N = V = R, is the larger part: its own error against
//             the brute force is 5-12% there, the card's <= 2.3%), and 0.1 at 3 light sizes (1.6%). 0.3 at 3
//             light sizes is the card's representative point (11.7% against the brute force; probe vs card
//             14%): 20%. At 0.1 the two part with distance (15% at 10, 35% at 30 light sizes) because the
//             probe cannot resolve the card: Frostbite's mapping reads roughness 0.1 at lod 2.85 of 10, whose
//             texels (1.4 degrees on 64-px faces) are as large as the card at 30 light sizes (1.9 degrees);
//             with 256-px faces 25% and 53%. Bounds there: 20% and 45%, so that the test catches it getting
//             worse.
double specularBound(float roughness, float distance) {
    if (roughness >= 0.5f || (roughness >= 0.2f && distance >= 5.0f)) return 0.15;
    if (roughness >= 0.2f) return 0.20;
    return distance < 5.0f ? 0.05 : distance < 20.0f ? 0.20 : 0.45;
}
TEST(LightCardProbe, MatchesTheTexturedLightAtADistance) {
    const AreaLight light = unitRectangle();
    const ImageRGBA emission = texturedEmission(64);
    const LightCardData card = bakeCard(emission, Executor::cpu());
    RuntimeOptions options;
    options.energyCompensation = false; // the area lights have none (runtime_area_lights.h)
    std::printf("| r | d | diffuse probe vs card | specular probe vs card | probe vs brute force (d / s) | "
                "card vs brute force (d / s) |\n|---|---|---|---|---|---|\n");
    for (float distance : kDistance) {
        const glm::vec3 position = sweepPoint(distance, kElevation, kAzimuth, 0.0f, 0.5f, {}).position;
        const CubeMap environment = rt_test::makeCube(
            kCubeSize, [&](glm::vec3 d) { return cardInEnvironment(light, emission, position, d); },
            kSupersample);
        const ProbeSet probe = rt_test::distantSet(environment, true);
        for (float roughness : kRoughness) {
            std::vector<ShadingPoint> points;
            for (const glm::vec3& target : kTargets)
                for (float view : kViewAngle)
                    points.push_back(sweepPoint(distance, kElevation, kAzimuth, view, roughness, target));
            const std::vector<ShadeResult> probed = shadeCpu(probe, points, options);
            const std::vector<AreaLightResult> textured = shadeTexturedLightCpu(light, card, points, options);
            const std::vector<AreaReference> reference =
                renderTexturedLightReference(light, emission, points, options);
            CellDifference c;
            for (std::size_t i = 0; i < points.size(); ++i) {
                const glm::dvec3 pd(glm::vec3(probed[i].diffuse)), ps(glm::vec3(probed[i].specular));
                const glm::dvec3 td(textured[i].diffuse), ts(textured[i].specular);
                c.diffuse += lumaError(pd, td);
                c.specular += lumaError(ps, ts);
                c.probeDiffuse += lumaError(pd, reference[i].value.diffuse);
                c.probeSpecular += lumaError(ps, reference[i].value.specular);
                c.texturedDiffuse += lumaError(td, reference[i].value.diffuse);
                c.texturedSpecular += lumaError(ts, reference[i].value.specular);
            }
            const double n = double(points.size());
            std::printf("| %.1f | %.0f | %.2f%% | %.2f%% | %.2f%% / %.2f%% | %.2f%% / %.2f%% |\n", roughness,
                        distance, 100.0 * c.diffuse / n, 100.0 * c.specular / n, 100.0 * c.probeDiffuse / n,
                        100.0 * c.probeSpecular / n, 100.0 * c.texturedDiffuse / n,
                        100.0 * c.texturedSpecular / n);
            SCOPED_TRACE("r " + std::to_string(roughness) + " d " + std::to_string(distance));
            EXPECT_LT(c.diffuse / n, 0.015);
            EXPECT_LT(c.specular / n, specularBound(roughness, distance));
        }
    }
}

} // namespace
