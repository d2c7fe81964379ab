// Shared helpers of the light-card tests (test_light_cards.cpp, test_light_card_probe.cpp): the unit
// rectangle light, textured and constant emissions normalized as the card's, the card's bake, and the
// sweep's shading points aimed at a point of the light.
#pragma once

#include <iblbake/baker/light_card.h>
#include <iblbake/opencl/executor.h>
#include <iblbake/runtime/runtime_light_card.h>

#include <cmath>

namespace ibl::test {

constexpr float kPi = 3.14159265358979f;
// Rec. 709 luminance, the card's normalization.
inline const glm::dvec3 kLuma(0.2126, 0.7152, 0.0722);

// A 1 x 1 rectangle at the origin emitting toward +z, its tangent +x, 1000 lm, white (the card colours it).
inline AreaLight unitRectangle() {
    return rectangleAreaLight(glm::vec3(0.0f), {0.0f, 0.0f, 1.0f}, {1.0f, 0.0f, 0.0f}, 1.0f, 1.0f,
                              glm::vec3(1.0f), 1000.0f);
}

// The emission normalized to mean luminance 1, as readLightCardTexture leaves it.
inline ImageRGBA normalized(ImageRGBA image) {
    double sum = 0.0;
    for (const glm::vec4& p : image.pixels)
        sum += glm::dot(glm::dvec3(glm::vec3(p)), kLuma);
    const float scale = float(double(image.pixels.size()) / sum);
    for (glm::vec4& p : image.pixels)
        p = glm::vec4(glm::vec3(p) * scale, 1.0f);
    return image;
}

// A card that varies in every channel at several scales: a red ramp along u, a green ramp down v, and a
// blue ripple of two periods, all positive (contrast 10:1 in red and green).
inline ImageRGBA texturedEmission(int size) {
    ImageRGBA image(size, size);
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
            const float u = (float(x) + 0.5f) / float(size), v = (float(y) + 0.5f) / float(size);
            image.at(x, y) =
                glm::vec4(0.2f + 1.8f * u, 0.2f + 1.8f * v,
                          1.0f + 0.8f * std::sin(4.0f * kPi * u) * std::sin(4.0f * kPi * v), 1.0f);
        }
    return normalized(image);
}

inline ImageRGBA constantEmission(int size, glm::vec3 colour) {
    ImageRGBA image(size, size);
    for (glm::vec4& p : image.pixels)
        p = glm::vec4(colour, 1.0f);
    return normalized(image);
}

inline LightCardData bakeCard(const ImageRGBA& emission, const Executor& executor, int layers = 8) {
    LightCardSettings settings;
    settings.size = emission.width;
    settings.diffuseLayers = layers;
    const LightCard card = bakeLightCard(emission, 1.0f, settings, executor);
    return lightCardData(card.layout, card.levels);
}

// A white dielectric at `distance` from the light's centre, `elevation` off its axis toward azimuth
// `azimuth`, its normal `viewAngle` off the direction to `target` (a point of the light) and its view the
// mirror image of that direction: the reflection points at `target`.
inline ShadingPoint sweepPoint(float distance, float elevation, float azimuth, float viewAngle,
                               float roughness, glm::vec3 target) {
    const glm::vec3 position =
        distance * glm::vec3(std::sin(elevation) * std::cos(azimuth), std::sin(elevation) * std::sin(azimuth),
                             std::cos(elevation));
    const glm::vec3 toTarget = glm::normalize(target - position);
    const glm::vec3 side = glm::normalize(glm::cross(toTarget, glm::vec3(0.0f, 1.0f, 0.0f)));
    const glm::vec3 normal = std::cos(viewAngle) * toTarget + std::sin(viewAngle) * side;
    const glm::vec3 view = 2.0f * glm::dot(normal, toTarget) * normal - toTarget;
    return makeShadingPoint(position, normal, view, glm::vec3(1.0f), 0.0f, roughness);
}

// |a - b| / |b| of the luminance, and the worst channel's.
inline double lumaError(glm::dvec3 a, glm::dvec3 b) {
    return std::abs(glm::dot(a - b, kLuma)) / glm::dot(b, kLuma);
}
inline double channelError(glm::dvec3 a, glm::dvec3 b) {
    const glm::dvec3 e = glm::abs(a - b) / b;
    return std::max({e.x, e.y, e.z});
}

} // namespace ibl::test
