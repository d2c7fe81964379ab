// The manifest's product entries (iblbake/baker/products.h).
#include "iblbake/baker/products.h"
#include "iblbake/core/error.h"
#include "iblbake/scene/json_vec3.h"

namespace ibl {

namespace {

using nlohmann::json;

} // namespace

json dfgManifestEntry(std::uint32_t size, std::uint32_t samples, bool disneyChannelUsed,
                      const std::string& contentHash) {
    return {{"file", "dfg_lut.ktx2"},
            {"format", "rgba32f"},
            {"size", size},
            {"samples", samples},
            {"layout", "x: NoV = (x+0.5)/N; y: perceptual roughness = (y+0.5)/N, first row first; "
                       "R = DFG1, G = DFG2, B = renormalized Disney diffuse"},
            {"disneyChannelUsed", disneyChannelUsed},
            {"contentHash", contentHash}};
}

json ldManifestFactsToJson(const LdManifestFacts& f) {
    json out = {{"file", f.file},
                {"format", f.format},
                {"faceSize", f.faceSize},
                {"levels", f.levels},
                {"integratedLevels", f.integratedLevels},
                {"roughnessMapping", mipMappingName(f.mapping)},
                {"roughnessMappingMeaning", mipMappingMeaning(f.mapping)},
                {"validRoughnessMax", f.validRoughnessMax},
                {"quality", f.quality}};
    if (f.sunInLevel0) out["sunInLevel0"] = *f.sunInLevel0;
    if (f.roughLayers) {
        json layers = {{"file", f.roughLayers->file},
                       {"faceSize", f.roughLayers->faceSize},
                       {"layerCount", IBL_ROUGH_LAYER_COUNT},
                       {"roughness", roughLayerRoughnessValues()},
                       {"meaning", roughLayerMeaning()}};
        layers.update(productStorageToJson(f.roughLayers->storage));
        out["roughLayers"] = std::move(layers);
    }
    return out;
}

LdManifestFacts ldManifestFactsFromJson(const json& j) {
    try {
        LdManifestFacts f;
        f.file = j.at("file").get<std::string>();
        f.format = j.at("format").get<std::string>();
        f.faceSize = j.at("faceSize").get<int>();
        f.levels = j.at("levels").get<int>();
        f.integratedLevels = j.at("integratedLevels").get<int>();
        const std::optional<MipMapping> mapping =
            mipMappingFromStoredValue(j.at("roughnessMapping").get<std::string>());
        if (!mapping)
            throw Error("LD manifest entry: roughnessMapping is not one of frostbite, linear, filament-lod");
        f.mapping = *mapping;
        f.validRoughnessMax = j.at("validRoughnessMax").get<double>();
        f.quality = j.at("quality").get<std::string>();
        if (j.contains("sunInLevel0")) f.sunInLevel0 = j["sunInLevel0"].get<bool>();
        if (j.contains("roughLayers")) {
            const json& layers = j["roughLayers"];
            f.roughLayers = LdManifestFacts::RoughLayers{layers.at("file").get<std::string>(),
                                                         layers.at("faceSize").get<int>(),
                                                         productStorageFromJson(layers)};
        }
        return f;
    } catch (const json::exception& e) {
        throw Error(std::string("LD manifest entry: ") + e.what());
    }
}

json probeVisibilityFactsToJson(const ProbeVisibilityFacts& f) {
    return {{"visibility", f.visibility},
            {"alphaRepaired",
             {{"nan", f.alphaNanRepaired},
              {"negative", f.alphaNegativeRepaired},
              {"overOne", f.alphaOverOneRepaired}}}};
}

ProbeVisibilityFacts probeVisibilityFactsFromJson(const json& j) {
    try {
        ProbeVisibilityFacts f;
        f.visibility = j.at("visibility").get<bool>();
        const json& repaired = j.at("alphaRepaired");
        f.alphaNanRepaired = repaired.at("nan").get<std::uint64_t>();
        f.alphaNegativeRepaired = repaired.at("negative").get<std::uint64_t>();
        f.alphaOverOneRepaired = repaired.at("overOne").get<std::uint64_t>();
        return f;
    } catch (const json::exception& e) {
        throw Error(std::string("probe visibility facts: ") + e.what());
    }
}

void addProbeVisibilityToManifest(json& entry, const ProbeVisibilityFacts& f) {
    if (f.visibility)
        entry["visibility"] = {
            {"convention", "premultiplied-alpha"},
            {"channel", "A"},
            {"meaning",
             "A = the capture's visibility filtered like RGB (1: close surroundings, 0: sky the "
             "composition takes from the next probe or the distant one, Frostbite 2014 4.9.5); RGB = "
             "LD of colour x visibility; KTX2 key iblbake.visibility = premultiplied-alpha"}};
    if (f.alphaNanRepaired + f.alphaNegativeRepaired + f.alphaOverOneRepaired > 0)
        entry["alphaRepaired"] = {{"nan", f.alphaNanRepaired},
                                  {"negative", f.alphaNegativeRepaired},
                                  {"overOne", f.alphaOverOneRepaired}};
}

json ldManifestEntry(const LdManifestFacts& facts, const std::string& contentHash) {
    json entry = ldManifestFactsToJson(facts);
    entry["contentHash"] = contentHash;
    return entry;
}

json diffuseManifestEntry(const json& doc, const std::string& contentHash) {
    const json& window = doc.at("sh").at("window");
    return {{"file", "diffuse.json"},
            {"sh",
             {{"irradiance", doc.at("sh").at("irradiance")},
              {"convention", "L2, DESIGN.md order, pre-scaled: Filament's irradianceSH(n) = "
                             "sum c_i p_i(n) returns the irradiance E(n) (1/pi not folded in)"},
              {"window",
               {{"name", window.at("name")},
                {"parameter", window.at("parameter")},
                {"searched", window.at("searched")},
                {"bandFactors", window.at("bandFactors")}}}}},
            {"contentHash", contentHash}};
}

json irradianceManifestEntry(int faceSize, const std::string& format, std::uint32_t samples,
                             const std::string& contentHash) {
    return {{"file", "irradiance.ktx2"},
            {"faceSize", faceSize},
            {"format", format},
            {"method", "sampled"},
            {"samples", samples},
            {"normalization",
             "E/pi: each texel stores the cosine-weighted mean radiance; irradiance E = pi x "
             "value"},
            {"contentHash", contentHash}};
}

json sunManifestEntry(const DiskLight& light, const std::string& contentHash) {
    return {{"file", "sun.json"},
            {"light",
             {{"direction", vec3Json(light.direction)},
              {"angularRadius", light.angularRadius},
              {"color", vec3Json(light.color)},
              {"illuminance", light.illuminance},
              {"meaning", "disk light toward direction, angular radius in radians, illuminance "
                          "perpendicular to it (lux when calibrated) times color"}}},
            {"contentHash", contentHash}};
}

void addCalibrationToManifest(json& manifest, const CalibrationRecord& record,
                              const std::string& colorSpace) {
    json metadata = json::object();
    for (const auto& [key, value] : calibrationMetadata(record, ""))
        metadata[key] = value;
    manifest["units"] = record.units();
    manifest["colorSpace"] = colorSpace;
    manifest["calibration"] = {{"factor", record.factor}, {"record", metadata}};
}

} // namespace ibl
