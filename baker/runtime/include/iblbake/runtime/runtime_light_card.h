// Textured rectangle lights for the runtime module (kernels/textured_light.h): a light card (the baker's
// `iblbake lightcard` product, kernels/light_card.h) loaded with its mapping, the light shaded on either
// backend, and the fp64 brute force over the textured rectangle.
#pragma once

#include "iblbake/core/image.h"
#include "iblbake/runtime/runtime_area_lights.h"

#include <textured_light.h>

#include <filesystem>
#include <span>
#include <vector>

namespace ibl {

// The card's KTX2 keys that the loader reads, as the baker writes them
// (baker/src/light_card/light_card_file.cpp).
namespace light_card_keys {
inline constexpr const char* kProduct = "iblbake.product"; // "light-card"
inline constexpr const char* kSpecularLevels = "iblbake.cardSpecularLevels";
inline constexpr const char* kDiffuseLayers = "iblbake.cardDiffuseLayers";
inline constexpr const char* kAspect = "iblbake.cardAspect";
inline constexpr const char* kMaxDistance = "iblbake.cardMaxDistance";
inline constexpr const char* kMaxFootprint = "iblbake.cardMaxFootprint";
inline constexpr const char* kProductName = "light-card";
} // namespace light_card_keys

// A card in memory: its layout (read from the file's iblbake.card* keys) and its texels in the order of
// kernels/light_card.h lightCardOffset (RGBA floats, level by level, layer by layer).
struct LightCardData {
    LightCardLayout layout{};
    std::vector<float> texels;
};

// Reads a light card's KTX2 file. Throws ibl::Error "<file>: <problem>" for a file that is no light card, a
// missing or malformed mapping key, or levels and layers that disagree with the keys.
LightCardData loadLightCard(const std::filesystem::path& path);
// The same from levels[m][layer] (as the baker's LightCard holds them) and the layout.
LightCardData lightCardData(const LightCardLayout& layout, const std::vector<std::vector<ImageRGBA>>& levels);

// The runtime's diffuse and specular of a textured rectangle light per point (kernels/textured_light.h),
// options as shadeAreaLightCpu. `light` is a rectangleAreaLight; its colour and power are the card's mean.
std::vector<AreaLightResult> shadeTexturedLightCpu(const AreaLight& light, const LightCardData& card,
                                                   std::span<const ShadingPoint> points,
                                                   const RuntimeOptions& options = {});
std::vector<AreaLightResult> shadeTexturedLightOpenCL(ocl::Context& context, const AreaLight& light,
                                                      const LightCardData& card,
                                                      std::span<const ShadingPoint> points,
                                                      const RuntimeOptions& options = {});

// The brute force of renderAreaLightReference over a rectangle whose radiance is light.color x
// light.luminance x emission(u, v), emission piecewise constant per texel (kernels/light_card.h's light
// space: u along the tangent, v = 0 at the +bitangent edge). The grid is a multiple of the emission's size,
// so every cell lies in one texel.
std::vector<AreaReference> renderTexturedLightReference(const AreaLight& light, const ImageRGBA& emission,
                                                        std::span<const ShadingPoint> points,
                                                        const RuntimeOptions& options = {},
                                                        const AreaReferenceSettings& settings = {});

} // namespace ibl
