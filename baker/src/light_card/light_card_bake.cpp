// The light card's bake (iblbake/baker/light_card.h): the specular chain and the diffuse layers of
// kernels/light_card.h, each texel by kernels/light_card_bake.h on OpenCL or TBB, and the file.
#include "iblbake/baker/light_card.h"
#include "iblbake/core/error.h"
#include "iblbake/core/numeric.h"
#include "iblbake/opencl/dispatch.h"

#include <light_card_bake.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstddef>

namespace ibl {

namespace {

static_assert(sizeof(LightCardBakeParams) == 32, "LightCardBakeParams must match light_card_bake.h");
static_assert(sizeof(LightCardLayout) == 32, "LightCardLayout must match light_card.h");

// A 2x2 box reduction (sizes powers of two; an axis of 1 stays 1).
ImageRGBA halve(const ImageRGBA& in) {
    const int w = std::max(1, in.width / 2), h = std::max(1, in.height / 2);
    const int sx = in.width > 1 ? 2 : 1, sy = in.height > 1 ? 2 : 1;
    ImageRGBA out(w, h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            glm::vec4 sum(0.0f);
            for (int j = 0; j < sy; ++j)
                for (int i = 0; i < sx; ++i)
                    sum += in.at(sx * x + i, sy * y + j);
            out.at(x, y) = sum / float(sx * sy);
        }
    return out;
}

// The emission's box pyramid, level 0 the emission.
std::vector<ImageRGBA> boxPyramid(const ImageRGBA& emission) {
    std::vector<ImageRGBA> pyramid{emission};
    while (pyramid.back().width > 1 || pyramid.back().height > 1)
        pyramid.push_back(halve(pyramid.back()));
    return pyramid;
}

// The coarsest pyramid level whose texels are at most beta / 4 on both axes (card units): the midpoint sum
// then resolves the kernel's core; level 0 when none is that fine.
std::size_t sourceLevelFor(const std::vector<ImageRGBA>& pyramid, float beta, float sizeU, float sizeV) {
    std::size_t level = 0;
    for (std::size_t s = 1; s < pyramid.size(); ++s) {
        const float texel = std::max(sizeU / float(pyramid[s].width), sizeV / float(pyramid[s].height));
        if (texel > 0.25f * beta) break;
        level = s;
    }
    return level;
}

// One output (a specular level or a diffuse layer) of width x height for kernel width beta.
ImageRGBA preIntegrate(const Dispatcher& dispatcher, const std::vector<ImageRGBA>& pyramid, int width,
                       int height, float beta, float sizeU, float sizeV) {
    const ImageRGBA& source = pyramid[sourceLevelFor(pyramid, beta, sizeU, sizeV)];
    LightCardBakeParams params{};
    params.width = std::uint32_t(width);
    params.height = std::uint32_t(height);
    params.sourceWidth = std::uint32_t(source.width);
    params.sourceHeight = std::uint32_t(source.height);
    params.invBetaSqr = 1.0f / (beta * beta);
    params.sizeU = sizeU;
    params.sizeV = sizeV;
    const float* data = &source.pixels.front().x;
    const std::span<const float> floats(data, source.pixels.size() * 4);
    DispatchOutput out = dispatcher.output(DispatchGrid::image(params.width, params.height));
    dispatcher.run(kernel("light_card.cl", "lightCardBake", lightCardBakeItem), out, params,
                   dispatcher.upload("light card source", floats));
    return dispatcher.downloadImage(out);
}

} // namespace

LightCardLayout lightCardLayout(const LightCardSettings& settings, float aspect) {
    if (!isPowerOfTwo(settings.size) || settings.size < 4 || settings.size > 4096)
        throw SettingError("size", "the card size " + std::to_string(settings.size) +
                                       " is not a power of two from 4 to 4096");
    if (settings.diffuseLayers < 2 || settings.diffuseLayers > 64)
        throw SettingError("layers", "the diffuse layer count " + std::to_string(settings.diffuseLayers) +
                                         " is not from 2 to 64");
    if (!(aspect > 0.0f) || !std::isfinite(aspect))
        throw SettingError("aspect", "the light's aspect " + std::to_string(aspect) + " is not positive");
    LightCardLayout layout{};
    layout.width = layout.height = std::uint32_t(settings.size);
    layout.levelCount = std::uint32_t(std::bit_width(layout.width)); // every level down to 1x1
    layout.diffuseLayers = std::uint32_t(settings.diffuseLayers);
    layout.aspect = aspect;
    layout.maxDistance = lightCardMaxDistance();
    return layout;
}

LightCard bakeLightCard(const ImageRGBA& emission, float aspect, const LightCardSettings& settings,
                        const Executor& executor) {
    LightCard card;
    card.layout = lightCardLayout(settings, aspect);
    if (emission.width != settings.size || emission.height != settings.size)
        throw Error("light card: the emission is " + std::to_string(emission.width) + "x" +
                    std::to_string(emission.height) + ", expected " + std::to_string(settings.size) + "x" +
                    std::to_string(settings.size));
    const float sizeU = std::sqrt(aspect), sizeV = 1.0f / sizeU;
    const std::vector<ImageRGBA> pyramid = boxPyramid(emission);
    const Dispatcher dispatcher(executor);
    const std::uint32_t layers = card.layout.diffuseLayers + 1;
    card.levels.resize(card.layout.levelCount);
    for (std::uint32_t m = 0; m < card.layout.levelCount; ++m) {
        std::vector<ImageRGBA>& level = card.levels[m];
        level.resize(layers);
        const int w = int(lightCardLevelSize(card.layout.width, m));
        const int h = int(lightCardLevelSize(card.layout.height, m));
        // Layer 0: the specular chain, level 0 the emission (a mirror's footprint), eq. 1.27 with beta = 2
        // rho_m.
        level[0] = m == 0 ? emission
                          : preIntegrate(dispatcher, pyramid, w, h,
                                         2.0f * lightCardLevelFootprint(card.layout, m), sizeU, sizeV);
        for (std::uint32_t k = 0; k < card.layout.diffuseLayers; ++k) {
            ImageRGBA& layer = level[1 + k];
            if (m > 0) {
                layer = halve(card.levels[m - 1][1 + k]);
                continue;
            }
            // Diffuse layer k: eq. 1.23's Diffuse_Lookup seen from distance r_k (beta = r_k); layer 0 at
            // r = 0 is the emission.
            const float r = lightCardLayerDistance(card.layout, k);
            layer = k == 0 ? emission : preIntegrate(dispatcher, pyramid, w, h, r, sizeU, sizeV);
        }
    }
    return card;
}

} // namespace ibl
