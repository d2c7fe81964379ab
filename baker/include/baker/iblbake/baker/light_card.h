// Light cards: a texture for a textured rectangle light, pre-integrated for the runtime (kernels/light_card.h
// holds the card's layout and the (roughness, distance) -> level / layer mapping; Drobot 1.3.5, 1.4.1).
#pragma once

#include "iblbake/core/image.h"
#include "iblbake/ktx2/ktx2.h"
#include "iblbake/opencl/executor.h"

#include <light_card.h>

#include <filesystem>
#include <string>
#include <vector>

namespace ibl {

struct LightCardSettings {
    int size = 256;        // level 0 is size x size texels (a power of two from 4 to 4096)
    int diffuseLayers = 8; // K, from 2 to 64
    Ktx2Format format = Ktx2Format::RGBA16F;
};

// The light's emission as the card stores it: linear RGB in the working space, mean luminance 1.
struct LightCardTexture {
    ImageRGBA emission;             // size x size, resampled from the input (box-filtered)
    float aspect = 1.0f;            // the input's width / height: the light's shape the card is baked for
    double sourceMeanLuminance = 0; // of the input in the working space, before normalizing
    std::string file, inputColorSpace, workingColorSpace;
};

// Reads a texture (any format OpenImageIO reads; integer files such as 8-bit PNG are taken as sRGB unless
// their metadata says otherwise, float files as linear Rec.709; inputColorSpace overrides) and converts it to
// `workingColorSpace` (linear), repairs NaN/Inf/negative texels, box-resamples it to size x size and
// normalizes it to mean luminance 1. Throws ibl::Error naming the file for an unreadable file or a texture
// without light.
LightCardTexture readLightCardTexture(const std::filesystem::path& file, const LightCardSettings& settings,
                                      const std::string& inputColorSpace = "",
                                      const std::string& workingColorSpace = "lin_rec709");

// The card: levels[m][layer], layer 0 the specular chain, layers 1..K the diffuse layers (light_card.h).
struct LightCard {
    LightCardLayout layout{};
    std::vector<std::vector<ImageRGBA>> levels;
};

// The layout of a card of these settings for a light of this aspect.
LightCardLayout lightCardLayout(const LightCardSettings& settings, float aspect);

// Bakes the card from a normalized emission (size x size) on the executor's backend (kernels/light_card.cl,
// or the same work-item on TBB). Throws ibl::SettingError for settings out of range.
LightCard bakeLightCard(const ImageRGBA& emission, float aspect, const LightCardSettings& settings,
                        const Executor& executor);

// The card's KTX2 keys: the product, the layout and mapping parameters the runtime loader reads back, the
// normalization and the colour spaces.
Ktx2KeyValues lightCardKeyValues(const LightCard& card, const LightCardTexture& texture);

// The flow of `iblbake lightcard` and a scene's light-card stage: read (in `workingColorSpace`), bake,
// write (all or nothing). Returns what the writer changed.
Ktx2WriteStats bakeLightCardFile(const std::filesystem::path& texture, const std::filesystem::path& output,
                                 const LightCardSettings& settings, const Executor& executor,
                                 const std::string& workingColorSpace = "lin_rec709");

} // namespace ibl
