// The bake summary (bake_state.h): stage statuses, counts, its JSON, and the summary of a bake found up to
// date. Free of backends and file formats, so that the front end (cli/front_end.cpp) links it alone.
#include "iblbake/bake_state/bake_state.h"

#include <cmath>
#include <cstdio>

namespace ibl {

namespace {

namespace fs = std::filesystem;

double secondsSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

} // namespace

const char* stageStatusName(StageStatus status) {
    switch (status) {
    case StageStatus::Ran:
        return "ran";
    case StageStatus::Cached:
        return "cached";
    case StageStatus::Failed:
        return "failed";
    default:
        return "pending";
    }
}

int BakeSummary::ran() const {
    int n = 0;
    for (const StageResult& s : stages)
        n += s.status == StageStatus::Ran;
    return n;
}

int BakeSummary::cached() const {
    int n = 0;
    for (const StageResult& s : stages)
        n += s.status == StageStatus::Cached;
    return n;
}

BakeSummary reportUpToDateBake(const Scene& scene, const UpToDate& upToDate, ProgressSink& progress,
                               std::chrono::steady_clock::time_point start) {
    const Plan plan = planScene(scene);
    BakeSummary summary;
    summary.skipped = plan.skipped;
    summary.backend = upToDate.backend;
    const int count = int(plan.stages.size());
    for (int i = 0; i < count; ++i) {
        const PlanStage& s = plan.stages[std::size_t(i)];
        summary.stages.push_back(
            {s.id, s.kind, StageStatus::Pending, upToDate.keys.at(std::size_t(i)), 0.0, s.products});
        progress.stageStart(summary.stages.back(), i, count);
        summary.stages.back().status = StageStatus::Cached;
        progress.stageEnd(summary.stages.back(), i, count);
    }
    summary.products = upToDate.products;
    summary.storage = upToDate.storage;
    summary.manifest = scene.outputs.directory / "manifest.json";
    summary.upToDate = true;
    summary.ok = true;
    addManifestReport(summary);
    summary.seconds = secondsSince(start);
    progress.done(summary);
    return summary;
}

std::vector<StoredProduct> storedProductsFromManifest(const nlohmann::json& manifest) {
    std::vector<StoredProduct> out;
    auto add = [&](const nlohmann::json& entry) {
        if (!entry.contains("storageScale")) return;
        StoredProduct p{entry.at("file").get<std::string>(),
                        entry.at("format").get<std::string>(),
                        entry["storageScale"].get<double>(),
                        entry.contains("storageClamp"),
                        {}};
        if (p.clamped)
            p.energyLostPercent = entry["storageClamp"].at("energyLostPercent").get<std::vector<double>>();
        out.push_back(std::move(p));
    };
    const nlohmann::json& products = manifest.at("products");
    for (const char* name : {"specular", "irradiance"})
        if (products.contains(name)) add(products[name]);
    for (const nlohmann::json& probe : products.value("probes", nlohmann::json::array()))
        add(probe);
    return out;
}

std::string storageLine(const StoredProduct& p) {
    char text[160];
    if (p.clamped) {
        std::string line = p.file + ": clamped to " + p.format + " on request, energy lost per level:";
        for (double percent : p.energyLostPercent) {
            std::snprintf(text, sizeof text, " %.3g%%", percent);
            line += text;
        }
        return line;
    }
    if (p.storageScale == 1.0) return p.file + ": fits " + p.format + " unscaled (storage scale 1)";
    std::snprintf(text, sizeof text,
                  ": stored x 2^%d (%.6g) to fit %s (iblbake.storageScale; readers divide)",
                  int(std::lround(std::log2(p.storageScale))), p.storageScale, p.format.c_str());
    return p.file + text;
}

nlohmann::json bakeSummaryJson(const BakeSummary& s) {
    nlohmann::json stages = nlohmann::json::array(), skipped = nlohmann::json::array(),
                   products = nlohmann::json::array();
    for (const StageResult& r : s.stages)
        stages.push_back({{"id", r.id},
                          {"kind", r.kind},
                          {"status", stageStatusName(r.status)},
                          {"key", r.key},
                          {"seconds", r.seconds},
                          {"products", r.products}});
    for (const SkippedStage& k : s.skipped)
        skipped.push_back({{"id", k.id}, {"kind", k.kind}, {"reason", k.reason}});
    for (const fs::path& p : s.products)
        products.push_back(p.string());
    nlohmann::json storage = nlohmann::json::array();
    for (const StoredProduct& p : s.storage) {
        storage.push_back({{"file", p.file},
                           {"format", p.format},
                           {"storageScale", p.storageScale},
                           {"clamped", p.clamped}});
        if (p.clamped) storage.back()["energyLostPercent"] = p.energyLostPercent;
    }
    nlohmann::json report = nlohmann::json::array();
    for (const ProductReport& r : s.report)
        report.push_back({{"name", r.name},
                          {"path", r.path.string()},
                          {"bytes", r.bytes},
                          {"files", r.files},
                          {"description", r.description}});
    nlohmann::json out = {{"ok", s.ok},
                          {"error", s.error},
                          {"backend", s.backend},
                          {"seconds", s.seconds},
                          {"upToDate", s.upToDate},
                          {"ran", s.ran()},
                          {"cached", s.cached()},
                          {"stages", stages},
                          {"skipped", skipped},
                          {"products", products},
                          {"manifest", s.manifest.string()},
                          {"storage", storage},
                          {"report", report},
                          {"calibration", s.calibration},
                          {"warnings", s.warnings}};
    if (s.previewError)
        out["previewError"] = {{"roughness", s.previewError->roughness},
                               {"dielectric", s.previewError->dielectric},
                               {"metal", s.previewError->metal}};
    return out;
}

} // namespace ibl
