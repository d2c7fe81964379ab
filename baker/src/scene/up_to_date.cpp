// checkBakeUpToDate (bake_scene.h): a finished bake is recognised from its manifest alone, so a batch killed
// and restarted skips it without starting OpenCL or touching the cache.
#include "iblbake/bake_scene.h"

#include "iblbake/content_hash.h"
#include "iblbake/error.h"
#include "stage_keys.h"

#include <nlohmann/json.hpp>

#include <fstream>

namespace ibl {

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

// Every {file, contentHash} the manifest lists (products.* and products.probes[]).
std::vector<std::pair<std::string, std::string>> listedProducts(const json& products) {
    std::vector<std::pair<std::string, std::string>> out;
    auto add = [&](const json& p) { out.emplace_back(p.at("file"), p.at("contentHash")); };
    for (const auto& [name, value] : products.items()) {
        if (name == "probes")
            for (const json& p : value)
                add(p);
        else
            add(value);
    }
    return out;
}

std::string check(const Scene& scene, const BakeOptions& options, std::vector<fs::path>& files) {
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

    const Plan plan = planScene(scene);
    const std::map<std::string, std::string> keys = planStageKeys(plan, hashPlanInputs(scene, plan), backend);
    const json& stages = manifest.at("stages");
    if (stages.size() != plan.stages.size()) return "the plan changed";
    for (std::size_t i = 0; i < stages.size(); ++i)
        if (stages[i].at("id") != plan.stages[i].id || stages[i].at("key") != keys.at(plan.stages[i].id))
            return "stage " + plan.stages[i].id + " has new inputs or settings";
    for (const auto& [product, hash] : listedProducts(manifest.at("products"))) {
        if (hashFile(scene.outputs.directory / product) != hash) return product + " changed";
        files.push_back(scene.outputs.directory / product);
    }
    files.push_back(file);
    return "";
}

} // namespace

UpToDate checkBakeUpToDate(const Scene& scene, const BakeOptions& options) {
    UpToDate out;
    if (options.force) {
        out.reason = "--force";
    } else {
        try {
            out.reason = check(scene, options, out.products);
        } catch (const std::exception& e) { // a missing product or input, a malformed manifest
            out.reason = e.what();
        }
    }
    out.upToDate = out.reason.empty();
    if (!out.upToDate) out.products.clear();
    return out;
}

} // namespace ibl
