// How product cubes go into their formats (iblbake/baker/products.h "Float storage").
#include "iblbake/bake_state/bake_state.h"
#include "iblbake/baker/products.h"
#include "iblbake/core/error.h"
#include "iblbake/ktx2/storage_scale.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace ibl {

namespace {

using nlohmann::json;

constexpr const char* kStorageScaleMeaning =
    "stored RGB = radiance x storageScale (pre-exposure, Frostbite 2014 section 5.2): a power of two chosen "
    "so that the product fits its format; readers divide by it (alpha is stored as is; absent means 1)";
constexpr const char* kStorageClampMeaning =
    "clamped to the format's range on request (outputs.clampToFormat): percent of each level's energy "
    "(sum of R+G+B x texel solid angle) lost";

// Shortest decimal text that reads back as the same double (powers of two have exact short forms).
std::string exactDecimal(double v) {
    char text[32];
    for (int digits = 1; digits <= 17; ++digits) {
        std::snprintf(text, sizeof text, "%.*g", digits, v);
        if (std::strtod(text, nullptr) == v) break;
    }
    return text;
}

bool isSignedFormat(Ktx2Format format) {
    return format == Ktx2Format::RGBA16F || format == Ktx2Format::RGBA32F;
}

} // namespace

double levelEnergy(const CubeMap& level) {
    double energy = 0.0;
    for (const ImageRGBA& face : level.faces)
        for (int y = 0; y < level.faceSize; ++y)
            for (int x = 0; x < level.faceSize; ++x) {
                const glm::vec4& t = face.at(x, y);
                double sum = 0.0;
                for (int c = 0; c < 3; ++c)
                    if (std::isfinite(t[c])) sum += t[c];
                energy += sum * texelSolidAngle(x, y, level.faceSize);
            }
    return energy;
}

ProductStorage chooseProductStorage(const CubeMapChain& chain, Ktx2Format format, bool clampToFormat) {
    const glm::vec3 largest = ktx2LargestValues(format);
    ProductStorage storage;
    if (clampToFormat) {
        storage.clamped = true;
        const glm::vec3 lowest = isSignedFormat(format) ? -largest : glm::vec3(0.0f);
        for (const CubeMap& level : chain.levels) {
            CubeMap clamped = level;
            for (ImageRGBA& face : clamped.faces)
                for (glm::vec4& t : face.pixels)
                    for (int c = 0; c < 3; ++c)
                        if (std::isfinite(t[c])) t[c] = std::fmin(std::fmax(t[c], lowest[c]), largest[c]);
            const double energy = levelEnergy(level);
            storage.energyLostPercent.push_back(
                energy > 0.0 ? 100.0 * (energy - levelEnergy(clamped)) / energy : 0.0);
        }
        return storage;
    }
    // The largest ratio of a finite channel to what the format stores of it.
    double ratio = 0.0;
    for (const CubeMap& level : chain.levels)
        for (const ImageRGBA& face : level.faces)
            for (const glm::vec4& t : face.pixels)
                for (int c = 0; c < 3; ++c)
                    if (std::isfinite(t[c])) ratio = std::fmax(ratio, std::fabs(double(t[c])) / largest[c]);
    // A power of two: multiplying by it (and the reader's division) changes only the exponent, so every
    // mantissa bit the format keeps is the one an unscaled value would keep; and its decimal text is exact.
    while (ratio * storage.scale > 1.0)
        storage.scale *= 0.5;
    return storage;
}

Ktx2KeyValues storageKeyValues(const ProductStorage& storage) {
    Ktx2KeyValues kv = {{kStorageScaleKey, exactDecimal(storage.scale)},
                        {"iblbake.storageScaleMeaning", kStorageScaleMeaning}};
    if (storage.clamped) {
        std::string levels;
        for (std::size_t m = 0; m < storage.energyLostPercent.size(); ++m) {
            char text[48];
            std::snprintf(text, sizeof text, "%slevel %zu %.4g%%", m ? ", " : "", m,
                          storage.energyLostPercent[m]);
            levels += text;
        }
        kv.emplace_back("iblbake.storageClamped", std::string(kStorageClampMeaning) + ": " + levels);
    }
    return kv;
}

namespace {

// The cubes with RGB times storage.scale (alpha kept), and the key/values with the storage's.
std::vector<CubeMap> scaledCubes(std::vector<CubeMap> cubes, const ProductStorage& storage) {
    const float scale = float(storage.scale);
    if (storage.scale != 1.0)
        for (CubeMap& cube : cubes)
            for (ImageRGBA& face : cube.faces)
                for (glm::vec4& t : face.pixels) {
                    t.r *= scale;
                    t.g *= scale;
                    t.b *= scale;
                }
    return cubes;
}

Ktx2KeyValues withStorageKeys(Ktx2KeyValues kv, const ProductStorage& storage) {
    for (auto& entry : storageKeyValues(storage))
        kv.push_back(std::move(entry));
    return kv;
}

} // namespace

Ktx2WriteStats writeProductCube(const std::filesystem::path& path, const CubeMapChain& chain,
                                Ktx2Format format, const Ktx2KeyValues& keyValues,
                                const ProductStorage& storage, Ktx2Alpha alpha) {
    const Ktx2KeyValues kv = withStorageKeys(keyValues, storage);
    if (storage.scale == 1.0) return writeKtx2Cube(path, chain, format, kv, alpha);
    return writeKtx2Cube(path, CubeMapChain{scaledCubes(chain.levels, storage)}, format, kv, alpha);
}

Ktx2WriteStats writeProductCubeArray(const std::filesystem::path& path, const std::vector<CubeMap>& layers,
                                     Ktx2Format format, const Ktx2KeyValues& keyValues,
                                     const ProductStorage& storage) {
    const Ktx2KeyValues kv = withStorageKeys(keyValues, storage);
    if (storage.scale == 1.0) return writeKtx2CubeArray(path, layers, format, kv);
    return writeKtx2CubeArray(path, scaledCubes(layers, storage), format, kv);
}

std::string storageText(const std::filesystem::path& file, const std::string& format,
                        const ProductStorage& storage) {
    return "storage " +
           storageLine({file.filename().string(), format, storage.scale, storage.clamped,
                        storage.energyLostPercent}) +
           "\n";
}

json productStorageToJson(const ProductStorage& storage) {
    json out = {{"storageScale", storage.scale}};
    if (storage.clamped)
        out["storageClamp"] = {{"energyLostPercent", storage.energyLostPercent},
                               {"meaning", kStorageClampMeaning}};
    return out;
}

ProductStorage productStorageFromJson(const json& j) {
    try {
        ProductStorage storage;
        storage.scale = j.at("storageScale").get<double>();
        if (j.contains("storageClamp")) {
            storage.clamped = true;
            storage.energyLostPercent = j["storageClamp"].at("energyLostPercent").get<std::vector<double>>();
        }
        return storage;
    } catch (const json::exception& e) {
        throw Error(std::string("storage record: ") + e.what());
    }
}

} // namespace ibl
