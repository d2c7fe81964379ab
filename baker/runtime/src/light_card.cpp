// Textured rectangle lights on either backend (kernels/textured_light.cl, its work-item
// kernels/textured_light_points.h) and the light card's loader (iblbake/runtime/runtime_light_card.h).
#include "area_light_dispatch.h"
#include "iblbake/core/error.h"
#include "iblbake/ktx2/ktx2.h"
#include "iblbake/opencl/dispatch.h"
#include "iblbake/runtime/runtime_light_card.h"

#include <textured_light_points.h>

#include <bit>
#include <charconv>
#include <cstddef>
#include <cstdlib>
#include <string>

namespace ibl {

namespace {

static_assert(sizeof(TexturedLightParams) == sizeof(AreaLight) + sizeof(LightCardLayout) + 12,
              "TexturedLightParams must match kernels/textured_light_points.h");

const std::string& requiredKey(const Ktx2Image& image, const std::string& key, const std::string& name) {
    auto it = image.keyValues.find(key);
    if (it == image.keyValues.end()) throw Error(name + ": no " + key + " key: not a light card");
    return it->second;
}

std::uint32_t keyCount(const Ktx2Image& image, const std::string& key, const std::string& name) {
    const std::string& text = requiredKey(image, key, name);
    std::uint32_t value = 0;
    auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (ec != std::errc() || end != text.data() + text.size())
        throw Error(name + ": " + key + " '" + text + "' is not a count");
    return value;
}

float keyFloat(const Ktx2Image& image, const std::string& key, const std::string& name) {
    const std::string& text = requiredKey(image, key, name);
    char* end = nullptr;
    const float value = std::strtof(text.c_str(), &end);
    if (text.empty() || *end != '\0' || !(value > 0.0f) || !std::isfinite(value))
        throw Error(name + ": " + key + " '" + text + "' is not a positive number");
    return value;
}

std::vector<AreaLightResult> shadeTexturedLight(const Dispatcher& dispatcher, const AreaLight& light,
                                                const LightCardData& card,
                                                std::span<const ShadingPoint> points,
                                                const RuntimeOptions& options) {
    if (light.shape != IBL_AREA_RECTANGLE) throw Error("a textured light must be a rectangle");
    const DeviceArray<ShadingPoint> input = dispatcher.upload("shading points", points);
    const DeviceArray<float> texels = dispatcher.upload("light card", card.texels);
    return shadeEachTerm(points.size(), options, [&](uint32_t flags) {
        TexturedLightParams params{};
        params.light = light;
        params.card = card.layout;
        params.flags = flags;
        params.dielectricF0 = options.dielectricF0;
        params.pointCount = uint32_t(points.size());
        DispatchOutput result = dispatcher.output(DispatchGrid::list(points.size()));
        dispatcher.run(kernel("textured_light.cl", "shadeTexturedLights", shadeTexturedLightItem), result,
                       params, input, texels);
        return dispatcher.download(result);
    });
}

} // namespace

LightCardData lightCardData(const LightCardLayout& layout,
                            const std::vector<std::vector<ImageRGBA>>& levels) {
    LightCardData card;
    card.layout = layout;
    if (levels.size() != layout.levelCount) throw Error("light card: level count disagrees with its layout");
    for (std::uint32_t m = 0; m < layout.levelCount; ++m) {
        if (levels[m].size() != layout.diffuseLayers + 1)
            throw Error("light card: level " + std::to_string(m) + " has " +
                        std::to_string(levels[m].size()) + " layers, its layout " +
                        std::to_string(layout.diffuseLayers + 1));
        for (const ImageRGBA& layer : levels[m]) {
            if (layer.width != int(lightCardLevelSize(layout.width, m)) ||
                layer.height != int(lightCardLevelSize(layout.height, m)))
                throw Error("light card: level " + std::to_string(m) + " has the wrong size");
            for (const glm::vec4& t : layer.pixels)
                card.texels.insert(card.texels.end(), {t.r, t.g, t.b, t.a});
        }
    }
    return card;
}

LightCardData loadLightCard(const std::filesystem::path& path) {
    const std::string name = path.string();
    const Ktx2Image image = readKtx2(path);
    namespace keys = light_card_keys;
    if (requiredKey(image, keys::kProduct, name) != keys::kProductName)
        throw Error(name + ": " + keys::kProduct + " is '" + image.keyValues.at(keys::kProduct) + "', not " +
                    keys::kProductName);
    LightCardLayout layout{};
    layout.width = image.pixelWidth;
    layout.height = image.pixelHeight;
    layout.levelCount = keyCount(image, keys::kSpecularLevels, name);
    layout.diffuseLayers = keyCount(image, keys::kDiffuseLayers, name);
    layout.aspect = keyFloat(image, keys::kAspect, name);
    layout.maxDistance = keyFloat(image, keys::kMaxDistance, name);
    // The mapping's constants are this build's (light_card.h); a card baked with others cannot be read right.
    if (keyFloat(image, keys::kMaxFootprint, name) != IBL_CARD_MAX_FOOTPRINT)
        throw Error(name + ": " + keys::kMaxFootprint + " differs from this runtime's " +
                    std::to_string(IBL_CARD_MAX_FOOTPRINT));
    if (layout.diffuseLayers < 2 || image.layerCount != layout.diffuseLayers + 1)
        throw Error(name + ": " + std::to_string(image.layerCount) + " layers, but " + keys::kDiffuseLayers +
                    " " + std::to_string(layout.diffuseLayers) + " needs " +
                    std::to_string(layout.diffuseLayers + 1));
    if (layout.levelCount != std::max<std::uint32_t>(1, image.levelCount) ||
        layout.levelCount != std::uint32_t(std::bit_width(std::max(layout.width, layout.height))))
        throw Error(name + ": " + std::to_string(image.levelCount) + " levels, " + keys::kSpecularLevels +
                    " " + std::to_string(layout.levelCount) + ": a card holds every level down to 1x1");
    try {
        return lightCardData(layout, image.levels);
    } catch (const Error& e) {
        throw Error(name + ": " + e.what());
    }
}

std::vector<AreaLightResult> shadeTexturedLightCpu(const AreaLight& light, const LightCardData& card,
                                                   std::span<const ShadingPoint> points,
                                                   const RuntimeOptions& options) {
    return shadeTexturedLight(Dispatcher(nullptr), light, card, points, options);
}

std::vector<AreaLightResult> shadeTexturedLightOpenCL(ocl::Context& context, const AreaLight& light,
                                                      const LightCardData& card,
                                                      std::span<const ShadingPoint> points,
                                                      const RuntimeOptions& options) {
    return shadeTexturedLight(Dispatcher(&context), light, card, points, options);
}

} // namespace ibl
