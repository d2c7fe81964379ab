// What a single-product command prints of its run (iblbake/baker/product_plans.h), from its stages' facts.
#include "iblbake/baker/product_plans.h"

#include "entry_files.h"

#include "iblbake/baker/inspect.h"
#include "iblbake/baker/products.h"
#include "iblbake/baker/sun.h"
#include "iblbake/core/format_text.h"

namespace ibl {

using nlohmann::json;

std::string environmentRunText(const ProductRun& run) {
    const std::map<std::string, json>& environment = run.facts.at("environment");
    std::optional<DiskLight> sun;
    if (const auto stage = run.facts.find("sun"); stage != run.facts.end())
        sun = diskLightFromJson(stage->second.at("calibration.json").at("sunLight").dump());
    return environment.at(kEntryFiles.ingestReport).at("text").get<std::string>() +
           preparationText(calibrationRecordFromJson(environment.at("calibration.json").at("record")), sun);
}

std::string specularRunText(const ProductPlan& plan, const ProductRun& run) {
    const json& settings = plan.plan.stages.back().settings;
    const std::string format = settings.at("ktx2Format").get<std::string>();
    const auto& facts = run.facts.at("specular");
    std::string text;
    for (const json& t : facts.at(kEntryFiles.chainReport).at("levels"))
        text += formatText("level %2d  r=%.4f  %4d px  %8.2f ms\n", t.at("level").get<int>(),
                           t.at("perceptualRoughness").get<double>(), t.at("faceSize").get<int>(),
                           t.at("milliseconds").get<double>());
    const LdManifestFacts written = ldManifestFactsFromJson(facts.at("manifest_facts.json"));
    const std::filesystem::path& chain = plan.files.at("specular.ktx2");
    const json& stats = facts.at(kEntryFiles.chainReport);
    text += formatText("wrote   %s: %zu levels, %s, %llu clamped texels, %llu repaired non-finite\n",
                       chain.string().c_str(), std::size_t(written.levels), format.c_str(),
                       stats.at("clampedTexels").get<unsigned long long>(),
                       stats.at("repairedNonFinite").get<unsigned long long>());
    text += storageText(chain, format, productStorageFromJson(facts.at("storage.json")));
    if (!written.roughLayers) return text;
    const std::filesystem::path& layers = plan.files.at(kRoughLayersFile);
    text += formatText("wrote   %s: %u rough layers of %u px (r = %s)\n", layers.string().c_str(),
                       IBL_ROUGH_LAYER_COUNT, std::uint32_t(written.roughLayers->faceSize),
                       roughLayerRoughnessText().c_str());
    return text + storageText(layers, format, written.roughLayers->storage);
}

std::string diffuseRunText(const ProductPlan& plan, const ProductRun& run) {
    std::string text = run.facts.at("diffuse").at(kEntryFiles.shReport).at("text").get<std::string>();
    const std::filesystem::path& document = plan.files.at("diffuse.json");
    const auto cube = run.facts.find("irradiance");
    if (cube == run.facts.end()) return text + formatText("wrote   %s\n", document.string().c_str());
    const json& settings = plan.plan.stages.back().settings;
    const std::string format = settings.at("ktx2Format").get<std::string>();
    const json& report = cube->second.at(kEntryFiles.irradianceReport);
    const std::filesystem::path& file = plan.files.at("irradiance.ktx2");
    text += formatText("cube    %d px %s, %s: %.1f ms, %llu clamped texels, %llu SH-negative texels\n",
                       settings.at("faceSize").get<int>(), settings.at("method").get<std::string>().c_str(),
                       format.c_str(), 1000.0 * run.stageSeconds("irradiance"),
                       report.at("clampedTexels").get<unsigned long long>(),
                       report.at("shNegativeTexels").get<unsigned long long>());
    text += storageText(file, format, productStorageFromJson(cube->second.at("storage.json")));
    return text + formatText("wrote   %s and %s\n", document.string().c_str(), file.string().c_str());
}

} // namespace ibl
