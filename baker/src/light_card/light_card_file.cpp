// The light card's document (its KTX2 keys) and the flow of `iblbake lightcard` (iblbake/baker/light_card.h).
#include "iblbake/baker/light_card.h"
#include "iblbake/core/numeric.h"
#include "iblbake/ktx2/atomic_file.h"
#include "iblbake/runtime/runtime_light_card.h"

namespace ibl {

Ktx2KeyValues lightCardKeyValues(const LightCard& card, const LightCardTexture& texture) {
    const LightCardLayout& l = card.layout;
    namespace keys = light_card_keys;
    return {{keys::kProduct, keys::kProductName},
            {"iblbake.cardLayout",
             "2D array; layer 0 level m: specular, the texture pre-integrated over a footprint of radius "
             "rho_m = " +
                 floatDecimal(IBL_CARD_MAX_FOOTPRINT) +
                 " * 2^(m-L+1) (level 0: rho 0), kernel 1/(1+x^2/(2 rho)^2)^2; layer 1+k level 0: diffuse, "
                 "seen from distance r_k = (k/(K-1))^2 r_max, kernel 1/(1+x^2/r^2)^2; lengths in "
                 "sqrt(light area); u along the tangent, v = 0 at the +bitangent edge; normalized sum T w / "
                 "sum w over the light"},
            {keys::kSpecularLevels, std::to_string(l.levelCount)},
            {keys::kMaxFootprint, floatDecimal(IBL_CARD_MAX_FOOTPRINT)},
            {keys::kDiffuseLayers, std::to_string(l.diffuseLayers)},
            {keys::kMaxDistance, floatDecimal(l.maxDistance)},
            {"iblbake.cardSigma", floatDecimal(IBL_CARD_SIGMA)},
            {keys::kAspect, floatDecimal(l.aspect)},
            {"iblbake.cardNormalization", "mean luminance 1 over the light"},
            {"iblbake.cardSourceMeanLuminance", floatDecimal(texture.sourceMeanLuminance)},
            {"iblbake.colorSpace", texture.workingColorSpace},
            {"iblbake.inputColorSpace", texture.inputColorSpace}};
}

Ktx2WriteStats bakeLightCardFile(const std::filesystem::path& texture, const std::filesystem::path& output,
                                 const LightCardSettings& settings, const Executor& executor,
                                 const std::string& workingColorSpace) {
    checkOutputFile(output); // before the work
    checkOutputExtension(output, ".ktx2");
    const LightCardTexture emission = readLightCardTexture(texture, settings, "", workingColorSpace);
    const LightCard card = bakeLightCard(emission.emission, emission.aspect, settings, executor);
    return writeKtx2Array(output, card.levels, settings.format, lightCardKeyValues(card, emission));
}

} // namespace ibl
