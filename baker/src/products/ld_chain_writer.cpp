// The LD chain's writers (product_writers.h): the KTX2 chain and its rough layers, which `iblbake specular`
// and the scene's specular and probe stages write, and the chain's debug OpenEXR levels.
#include "iblbake/baker/exr_output.h"
#include "iblbake/baker/product_writers.h"
#include "iblbake/ktx2/cube_profile.h"
#include "iblbake/runtime/runtime.h"

#include <nlohmann/json.hpp>

namespace ibl {

namespace fs = std::filesystem;

LdChainWritten writeLdChainProduct(OutputSet& outputs, SpecularWithRoughLayers& baked,
                                   const LdChainWriteSettings& settings, const CalibrationRecord& record,
                                   const std::optional<DiskLight>& sun, const fs::path& chainFile,
                                   const fs::path& roughLayersFile) {
    CubeMapChain& chain = baked.chain;
    LdChainProduct product = settings.product;
    // Before the storage is chosen: level 0 with the sun decides the scale.
    product.sunInLevel0 = settings.withSun &&
                          keepSunInLevel0(chain, *settings.withSun, settings.format, settings.clampToFormat);
    LdChainWritten written;
    written.sunInLevel0 = product.sunInLevel0;
    written.chain.storage = chooseProductStorage(chain, settings.format, settings.clampToFormat);
    Ktx2KeyValues keyValues = ldChainKeyValues(product, record, sun);
    keyValues.emplace_back(kCubeProfileKey, settings.profile);
    if (settings.visibility) keyValues.emplace_back(kVisibilityKey, kVisibilityPremultipliedAlpha);
    outputs.writeFile(chainFile, [&](const fs::path& temporary) {
        written.chain.stats =
            writeProductCube(temporary, chain, settings.format, keyValues, written.chain.storage,
                             settings.visibility ? Ktx2Alpha::Premultiplied : Ktx2Alpha::Straight);
    });
    if (baked.roughLayers.empty()) return written;
    const std::vector<CubeMap>& layers = baked.roughLayers;
    StoredCube& stored = written.roughLayers.emplace();
    stored.storage = chooseProductStorage(CubeMapChain{layers}, settings.format, settings.clampToFormat);
    Ktx2KeyValues layerKeyValues = roughLayerKeyValues(product, record, sun);
    layerKeyValues.emplace_back(kCubeProfileKey, settings.profile);
    outputs.writeFile(roughLayersFile, [&](const fs::path& temporary) {
        stored.stats =
            writeProductCubeArray(temporary, layers, settings.format, layerKeyValues, stored.storage);
    });
    return written;
}

void writeLdChainExrLevels(OutputSet& outputs, const CubeMapChain& chain, const LdChainProduct& product,
                           const fs::path& directory) {
    const bool engineLevels = !product.levelRoughness.empty();
    outputs.writeDirectory(directory, [&](const fs::path& temporary) {
        for (std::size_t m = 0; m < chain.levels.size(); ++m) {
            const CubeMap& level = chain.levels[m];
            ImageRGBA strip(6 * level.faceSize, level.faceSize);
            for (int f = 0; f < 6; ++f)
                for (int y = 0; y < level.faceSize; ++y)
                    for (int x = 0; x < level.faceSize; ++x)
                        strip.at(f * level.faceSize + x, y) = level.faces[f].at(x, y);
            ExrOutputOptions exr;
            exr.channels = 3;
            exr.attributes = {
                {"iblbake:layout", "horizontal strip +X,-X,+Y,-Y,+Z,-Z, OpenGL face orientation"},
                {"iblbake:level", std::to_string(m)},
                {"iblbake:roughnessMapping",
                 engineLevels ? kFilamentLodRuleName : mipMappingName(product.mapping)},
                {"iblbake:roughnessMappingMeaning",
                 engineLevels ? kFilamentLodRuleMeaning : mipMappingMeaning(product.mapping)}};
            if (engineLevels)
                exr.attributes.emplace_back("iblbake:levelRoughness",
                                            nlohmann::json(product.levelRoughness.at(m)).dump());
            writeExr(temporary / ("level_" + std::to_string(m) + ".exr"), strip, exr);
        }
    });
}

} // namespace ibl
