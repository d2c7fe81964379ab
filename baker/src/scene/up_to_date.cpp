// checkBakeUpToDate (bake_state.h): a finished bake is recognised from its manifest and the content hashes
// alone, so a re-run of an unchanged scene (and a batch killed and restarted) starts no backend and reads
// no cache entry.
#include "iblbake/bake_state/bake_state.h"

#include "iblbake/bake_state/code_identity.h"
#include "iblbake/bake_state/content_hash.h"
#include "iblbake/core/error.h"
#include "iblbake/scene/scene_lights.h"
#include "stage_keys.h"

#include <nlohmann/json.hpp>

#include <fstream>

namespace ibl {

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

// File -> contentHash of every product the manifest lists (products.*, products.probes[] and
// products.lightCards[], the files[] of a product made of several: a glTF's images, a preview's EXR; and
// the specular chain's roughLayers).
std::map<std::string, std::string> listedHashes(const json& products) {
    std::map<std::string, std::string> out;
    auto add = [&](const json& p) {
        out[p.at("file")] = p.at("contentHash");
        if (p.contains("files"))
            for (const json& f : p["files"])
                out[f.at("file")] = f.at("contentHash");
        if (p.contains("roughLayers")) out[p["roughLayers"].at("file")] = p["roughLayers"].at("contentHash");
    };
    for (const auto& [name, value] : products.items()) {
        if (name == "lights") continue; // their cards are in lightCards
        if (name == "probes" || name == "lightCards")
            for (const json& p : value)
                add(p);
        else
            add(value);
    }
    return out;
}

std::string check(const Scene& scene, const BakeOptions& options, UpToDate& out) {
    const fs::path file = scene.outputs.directory / "manifest.json";
    std::ifstream in(file);
    if (!in) return "no manifest.json";
    json manifest;
    try {
        manifest = json::parse(in);
    } catch (const json::exception&) {
        return "manifest.json is not valid JSON";
    }
    const std::string backend = manifest.value("backend", "");
    if ((options.backend == Backend::OpenCL && backend == "cpu") ||
        (options.backend == Backend::Cpu && backend == "opencl"))
        return "baked with the " + backend + " backend";

    if (manifest.value("manifestCode", "") != builtInStageCodeIdentity().at("manifest"))
        return "manifest.json was written by other code";

    const Plan plan = planScene(scene);
    out.inputHashes = hashPlanInputs(scene, plan);
    const std::map<std::string, std::string> keys = planStageKeys(plan, out.inputHashes, backend);
    const json& stages = manifest.at("stages");
    if (stages.size() != plan.stages.size()) return "the plan changed";
    for (std::size_t i = 0; i < stages.size(); ++i) {
        const std::string& key = keys.at(plan.stages[i].id);
        if (stages[i].at("id") != plan.stages[i].id || stages[i].at("key") != key)
            return "stage " + plan.stages[i].id + " has new inputs or settings";
        out.keys.push_back(key);
    }
    if (manifest.at("products").value("lights", json::array()) != sceneLightsJson(scene))
        return "the scene's lights changed";
    const std::map<std::string, std::string> hashes = listedHashes(manifest.at("products"));
    for (const PlanStage& stage : plan.stages)
        for (const std::string& product : stage.products) {
            const auto listed = hashes.find(product);
            if (listed == hashes.end()) return "manifest.json does not list " + product;
            if (hashFile(scene.outputs.directory / product) != listed->second) return product + " changed";
            out.products.push_back(scene.outputs.directory / product);
        }
    out.products.push_back(file);
    out.backend = backend;
    out.storage = storedProductsFromManifest(manifest);
    return "";
}

} // namespace

UpToDate checkBakeUpToDate(const Scene& scene, const BakeOptions& options) {
    UpToDate out;
    if (options.force) {
        out.reason = "--force";
    } else {
        try {
            // A scene the bake would refuse is not answered from its old bake.
            const std::optional<std::string> refusal = refusalBeforeWork(scene, planScene(scene), options);
            out.reason = refusal ? *refusal : check(scene, options, out);
        } catch (const std::exception& e) { // a missing product or input, a malformed manifest
            out.reason = e.what();
        }
    }
    out.upToDate = out.reason.empty();
    if (!out.upToDate) out = UpToDate{false, out.reason, {}, {}, {}, {}, std::move(out.inputHashes)};
    return out;
}

} // namespace ibl
