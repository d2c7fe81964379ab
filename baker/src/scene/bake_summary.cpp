// The bake summary (bake_state.h): stage statuses, counts, its JSON, and the summary of a bake found up to
// date. Free of backends and file formats, so that the front end (cli/front_end.cpp) links it alone.
#include "iblbake/bake_state/bake_state.h"

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
    summary.manifest = scene.outputs.directory / "manifest.json";
    summary.upToDate = true;
    summary.ok = true;
    addManifestReport(summary);
    summary.seconds = secondsSince(start);
    progress.done(summary);
    return summary;
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
                          {"report", report},
                          {"calibration", s.calibration}};
    if (s.previewError)
        out["previewError"] = {{"roughness", s.previewError->roughness},
                               {"dielectric", s.previewError->dielectric},
                               {"metal", s.previewError->metal}};
    return out;
}

} // namespace ibl
