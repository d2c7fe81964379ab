// KTX2 key/values of the LD chains, the irradiance cube and the DFG LUT (iblbake/baker/products.h).
#include "iblbake/baker/products.h"
#include "iblbake/core/error.h"
#include "iblbake/ktx2/cube_profile.h"

namespace ibl {

const char* const kLatLongPixelsKey = "latlongPixels";

Ktx2KeyValues latLongPixelsKeyValues(const std::optional<LatLongPixels>& placement,
                                     const std::string& prefix) {
    if (!placement) return {};
    return {{prefix + kLatLongPixelsKey, latLongPixelsName(*placement)}};
}

void addLatLongPixels(nlohmann::json& object, const std::optional<LatLongPixels>& placement) {
    if (placement) object[kLatLongPixelsKey] = latLongPixelsName(*placement);
}

std::optional<LatLongPixels> latLongPixelsFromJson(const nlohmann::json& object) {
    if (!object.contains(kLatLongPixelsKey)) return std::nullopt;
    const nlohmann::json& value = object[kLatLongPixelsKey];
    const LatLongPixels placement =
        value.is_string() ? parseLatLongPixels(value.get<std::string>()) : LatLongPixels::Auto;
    if (placement == LatLongPixels::Auto)
        throw Error(std::string(kLatLongPixelsKey) + ": " + value.dump() + " is not centre or openexr");
    return placement;
}

Ktx2KeyValues dfgLutMetadata(const std::string& prefix, const std::string& rowWord, std::uint32_t samples) {
    return {{prefix + "product", "dfg-lut"},
            {prefix + "layout",
             "x: NoV=(x+0.5)/N; y: perceptualRoughness=(y+0.5)/N from the first " + rowWord +
                 "; R=DFG1=E[(1-Fc)GVis] G=DFG2=E[Fc GVis] (Frostbite Listing 18, height-correlated Smith "
                 "GGX); B=renormalized Disney diffuse (Frostbite Listing 1)"},
            {prefix + "samples", std::to_string(samples)}};
}

Ktx2KeyValues ldChainKeyValues(const LdChainProduct& c, const CalibrationRecord& record,
                               const std::optional<DiskLight>& sun) {
    const bool engineLevels = !c.levelRoughness.empty(); // the levels follow an engine profile's rule
    Ktx2KeyValues kv = {
        {"iblbake.product", c.product},
        {"iblbake.roughnessMapping", engineLevels ? kFilamentLodRuleName : mipMappingName(c.mapping)},
        {"iblbake.roughnessMappingMeaning",
         engineLevels ? kFilamentLodRuleMeaning : mipMappingMeaning(c.mapping)},
        {"iblbake.levelCount", std::to_string(c.levelCount)},
        {"iblbake.colorSpace", c.colorSpace},
        {"iblbake.settings", c.settings}};
    if (engineLevels) {
        std::string list;
        for (std::size_t m = 0; m < c.levelRoughness.size(); ++m)
            list += (m ? ", " : "") + nlohmann::json(c.levelRoughness[m]).dump();
        kv.emplace_back("iblbake.levelRoughness", list);
    }
    if (c.integratedLevels) kv.emplace_back("iblbake.integratedLevels", std::to_string(*c.integratedLevels));
    if (c.source) kv.emplace_back("iblbake.source", *c.source);
    for (auto& entry : latLongPixelsKeyValues(c.latLongPixels))
        kv.push_back(std::move(entry));
    for (auto& entry : calibrationKeyValues(record, sun))
        kv.push_back(std::move(entry));
    if (c.sunInLevel0) {
        kv.emplace_back("iblbake.sunInLevel0", "true");
        if (c.sunMaxSolidAngle)
            kv.emplace_back("iblbake.sunMaxSolidAngle", std::to_string(*c.sunMaxSolidAngle));
    }
    return kv;
}

Ktx2KeyValues roughLayerKeyValues(const LdChainProduct& c, const CalibrationRecord& record,
                                  const std::optional<DiskLight>& sun) {
    Ktx2KeyValues kv = {{"iblbake.product", kRoughLayerProduct},
                        {kRoughLayerRoughnessKey, roughLayerRoughnessText()},
                        {"iblbake.roughLayerMeaning", roughLayerMeaning()},
                        {"iblbake.colorSpace", c.colorSpace},
                        {"iblbake.settings", c.settings}};
    if (c.source) kv.emplace_back("iblbake.source", *c.source);
    for (auto& entry : latLongPixelsKeyValues(c.latLongPixels))
        kv.push_back(std::move(entry));
    for (auto& entry : calibrationKeyValues(record, sun))
        kv.push_back(std::move(entry));
    return kv;
}

const char* const kIrradianceNormalization =
    "E/pi: each texel stores (1/pi) integral L(l) max(0,n.l) dl, the cosine-weighted mean radiance "
    "(Frostbite Listing 20's LD of a Lambert lobe); irradiance E = pi x value";

std::string irradianceMethodText(IrradianceMethod method, std::uint32_t samples) {
    if (method == IrradianceMethod::SH)
        return "sh: the windowed L2 irradiance SH evaluated at each texel centre, negatives clamped to 0";
    return "sampled: cosine importance sampling, " + std::to_string(samples) +
           " samples/texel, pre-filtered lookups (Frostbite Listing 20 + Listing 19 LOD), bright texels "
           "integrated exactly";
}

Ktx2KeyValues irradianceKeyValues(const std::string& methodText, const std::string& colorSpace,
                                  const std::optional<std::string>& source,
                                  const std::optional<LatLongPixels>& latLongPixels,
                                  const CalibrationRecord& record, const std::optional<DiskLight>& sun) {
    Ktx2KeyValues kv = {{"iblbake.product", "irradiance"},
                        {"iblbake.irradianceNormalization", kIrradianceNormalization},
                        {"iblbake.method", methodText},
                        {"iblbake.colorSpace", colorSpace}};
    if (source) kv.emplace_back("iblbake.source", *source);
    for (auto& entry : latLongPixelsKeyValues(latLongPixels))
        kv.push_back(std::move(entry));
    for (auto& entry : calibrationKeyValues(record, sun))
        kv.push_back(std::move(entry));
    return kv;
}

} // namespace ibl
