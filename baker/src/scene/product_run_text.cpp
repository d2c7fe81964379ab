// What a single-product command prints of its run (iblbake/baker/product_plans.h), from its stages' facts.
#include "iblbake/baker/product_plans.h"

#include "iblbake/baker/products.h"
#include "iblbake/baker/sun.h"
#include "iblbake/core/format_text.h"

namespace ibl {

namespace {

using nlohmann::json;

std::string storageText(const std::filesystem::path& file, const std::string& format, const json& storage) {
    const ProductStorage s = productStorageFromJson(storage);
    return "storage " +
           storageLine({file.filename().string(), format, s.scale, s.clamped, s.energyLostPercent}) + "\n";
}

} // namespace

std::string environmentRunText(const ProductRun& run) {
    const json& r = run.facts.at("environment").at(kIngestReportFile);
    std::string text = formatText(
        "input   %s: %dx%d %s, %s -> %s, max luminance %.6g\n", r.at("file").get<std::string>().c_str(),
        r.at("width").get<int>(), r.at("height").get<int>(), r.at("layout").get<std::string>().c_str(),
        r.at("inputColorSpace").get<std::string>().c_str(),
        r.at("workingColorSpace").get<std::string>().c_str(), r.at("maxLuminanceIn").get<double>());
    text += formatText("repaired NaN %llu, Inf %llu, negative %llu channel values\n",
                       r.at("nanRepaired").get<unsigned long long>(),
                       r.at("infRepaired").get<unsigned long long>(),
                       r.at("negativeRepaired").get<unsigned long long>());
    const CalibrationRecord record =
        calibrationRecordFromJson(run.facts.at("environment").at("calibration.json").at("record"));
    if (record.absolute()) text += record.summary() + "\n";
    const auto sun = run.facts.find("sun");
    if (sun == run.facts.end()) return text;
    const DiskLight light = diskLightFromJson(sun->second.at("calibration.json").at("sunLight").dump());
    return text + formatText("sun     extracted: %.6g lux at elevation %.2f deg, azimuth %.2f deg\n",
                             light.illuminance, light.elevationDegrees(), light.azimuthDegrees());
}

std::string specularRunText(const ProductPlan& plan, const ProductRun& run) {
    const json& settings = plan.plan.stages.back().settings;
    const std::string format = settings.at("ktx2Format").get<std::string>();
    const auto& facts = run.facts.at("specular");
    std::string text;
    for (const json& t : facts.at(kChainReportFile).at("levels"))
        text += formatText("level %2d  r=%.4f  %4d px  %8.2f ms\n", t.at("level").get<int>(),
                           t.at("perceptualRoughness").get<double>(), t.at("faceSize").get<int>(),
                           t.at("milliseconds").get<double>());
    const LdManifestFacts written = ldManifestFactsFromJson(facts.at("manifest_facts.json"));
    const std::filesystem::path& chain = plan.files.at("specular.ktx2");
    const json& stats = facts.at(kChainReportFile);
    text += formatText("wrote   %s: %zu levels, %s, %llu clamped texels, %llu repaired non-finite\n",
                       chain.string().c_str(), std::size_t(written.levels), format.c_str(),
                       stats.at("clampedTexels").get<unsigned long long>(),
                       stats.at("repairedNonFinite").get<unsigned long long>());
    text += storageText(chain, format, facts.at("storage.json"));
    if (!written.roughLayers) return text;
    const std::filesystem::path& layers = plan.files.at(kRoughLayersFile);
    text += formatText("wrote   %s: %u rough layers of %u px (r = %s)\n", layers.string().c_str(),
                       IBL_ROUGH_LAYER_COUNT, std::uint32_t(written.roughLayers->faceSize),
                       roughLayerRoughnessText().c_str());
    return text + storageText(layers, format, productStorageToJson(written.roughLayers->storage));
}

} // namespace ibl
