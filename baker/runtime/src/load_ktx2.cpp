// Loading the baker's KTX2 products (readKtx2 has no OIIO dependency).
#include "iblbake/core/error.h"
#include "iblbake/ktx2/ktx2.h"
#include "iblbake/ktx2/storage_scale.h"
#include "iblbake/runtime/runtime.h"

namespace ibl {

namespace {

// A product file's texels in radiance: divided by its storage scale (storage_scale.h), so that shading is
// the same whatever scale the file was stored with.
Ktx2Image readProductKtx2(const std::filesystem::path& path) {
    Ktx2Image image = readKtx2(path);
    try {
        unscaleKtx2Texels(image);
    } catch (const Error& e) {
        throw Error(path.string() + ": " + e.what());
    }
    return image;
}

// Images first .. first + 5 of a KTX2 level (a cube's faces in order; a cube array's layers follow one
// another) as a cube map, moved out of the level: no face is allocated or copied on the way.
CubeMap takeCube(std::vector<ImageRGBA>& level, std::size_t first) {
    CubeMap cube;
    cube.faceSize = level.at(first).width;
    for (std::size_t f = 0; f < 6; ++f)
        cube.faces[f] = std::move(level.at(first + f));
    return cube;
}

} // namespace

LdPyramid loadLdKtx2(const std::filesystem::path& path) {
    Ktx2Image image = readProductKtx2(path);
    if (image.faceCount != 6)
        throw Error(path.string() + ": not a cube map (" + std::to_string(image.faceCount) + " faces)");
    if (image.pixelWidth != image.pixelHeight) throw Error(path.string() + ": cube faces are not square");
    CubeMapChain chain;
    for (std::vector<ImageRGBA>& level : image.levels)
        chain.levels.push_back(takeCube(level, 0));
    MipMapping mapping = MipMapping::Frostbite;
    auto it = image.keyValues.find("iblbake.roughnessMapping");
    try {
        if (it != image.keyValues.end()) mapping = parseStoredMipMapping(it->second);
        ChainAlpha alpha = ChainAlpha::Ignore; // files without the key (older bakes): RGB is the colour
        if (auto visibility = image.keyValues.find(kVisibilityKey); visibility != image.keyValues.end()) {
            if (visibility->second != kVisibilityPremultipliedAlpha)
                throw Error(std::string(kVisibilityKey) + " " + quotedForMessage(visibility->second) +
                            " is not " + kVisibilityPremultipliedAlpha);
            if (image.vkFormat != 97u && image.vkFormat != 109u) // RGBA16F, RGBA32F (ktx2.h)
                throw Error(std::string(kVisibilityKey) + ": the format has no alpha channel");
            alpha = ChainAlpha::PremultipliedVisibility;
        }
        LdPyramid pyramid = ldPyramidFromChain(chain, mapping, alpha);
        auto sun = image.keyValues.find("iblbake.sunInLevel0");
        pyramid.sunInLevel0 = sun != image.keyValues.end() && sun->second == "true";
        return pyramid;
    } catch (const Error& e) {
        throw Error(path.string() + ": " + e.what());
    }
}

std::vector<CubeMap> loadRoughLayersKtx2(const std::filesystem::path& path) {
    Ktx2Image image = readProductKtx2(path);
    const std::string name = path.string();
    if (image.faceCount != 6 || image.layerCount != IBL_ROUGH_LAYER_COUNT || image.levels.size() != 1)
        throw Error(name + ": not a cube map array of " + std::to_string(IBL_ROUGH_LAYER_COUNT) +
                    " layers and one level (" + std::to_string(image.layerCount) + " layers, " +
                    std::to_string(image.faceCount) + " faces, " + std::to_string(image.levels.size()) +
                    " levels)");
    // Layers of another grid would be read at the wrong roughness: the file must name this one.
    const std::string expected = roughLayerRoughnessText();
    auto grid = image.keyValues.find(kRoughLayerRoughnessKey);
    if (grid == image.keyValues.end())
        throw Error(name + ": " + kRoughLayerRoughnessKey + " is missing (expected " + expected + ")");
    if (grid->second != expected)
        throw Error(name + ": " + kRoughLayerRoughnessKey + " " + quotedForMessage(grid->second) +
                    " is another grid than this runtime's (" + expected + ")");
    std::vector<CubeMap> layers;
    for (std::uint32_t k = 0; k < IBL_ROUGH_LAYER_COUNT; ++k)
        layers.push_back(takeCube(image.levels[0], 6 * std::size_t(k)));
    return layers;
}

CubeMap loadIrradianceKtx2(const std::filesystem::path& path) {
    Ktx2Image image = readProductKtx2(path);
    if (image.faceCount != 6 || image.levels.empty())
        throw Error(path.string() + ": not a cube map (" + std::to_string(image.faceCount) + " faces)");
    if (image.pixelWidth != image.pixelHeight) throw Error(path.string() + ": cube faces are not square");
    return takeCube(image.levels[0], 0);
}

DfgTable loadDfgKtx2(const std::filesystem::path& path) {
    Ktx2Image image = readKtx2(path);
    if (image.faceCount != 1 || image.levels.empty() || image.levels[0].empty())
        throw Error(path.string() + ": not a 2D image");
    try {
        return dfgTableFromImage(image.levels[0][0]);
    } catch (const Error& e) {
        throw Error(path.string() + ": " + e.what());
    }
}

} // namespace ibl
