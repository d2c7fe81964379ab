#include "iblbake/batch_run/batch_progress.h"

#include <cstdio>

namespace ibl {

void BatchProgress::event(const std::string& name, nlohmann::json event) {
    if (mode_ != ProgressMode::Json) return;
    event["event"] = name;
    const std::string text = event.dump();
    std::lock_guard lock(mutex_);
    std::printf("%s\n", text.c_str());
    std::fflush(stdout); // a watcher (or a scheduler's log) sees each event as it happens
}

void BatchProgress::line(const std::string& text, bool isError) {
    if (mode_ == ProgressMode::Json || (mode_ == ProgressMode::Quiet && !isError)) return;
    std::lock_guard lock(mutex_);
    std::fprintf(stderr, "%s\n", text.c_str());
}

void BatchProgress::batchStart(const BatchSummary& summary, const std::filesystem::path& summaryFile) {
    event("batch-start", {{"items", summary.items.size()},
                          {"inShard", summary.items.size() - summary.count(BatchItemStatus::NotInShard)},
                          {"shard", batchShardJson(summary.shard)},
                          {"jobs", summary.jobs},
                          {"summary", summaryFile.string()}});
}

void BatchProgress::itemStart(const BatchItem& item) {
    event("item-start", {{"item", item.id}, {"index", item.index}});
}

void BatchProgress::stageStart(const BatchItem& item, const StageResult& stage, int index, int count) {
    event("stage-start",
          {{"item", item.id}, {"stage", stage.id}, {"kind", stage.kind}, {"index", index}, {"count", count}});
}

void BatchProgress::stageEnd(const BatchItem& item, const StageResult& stage, int index, int count) {
    event("stage-end", {{"item", item.id},
                        {"stage", stage.id},
                        {"status", stageStatusName(stage.status)},
                        {"cached", stage.status == StageStatus::Cached},
                        {"seconds", stage.seconds}});
    char text[160];
    std::snprintf(text, sizeof text, "%d/%d %-20s %-7s %.2f s", index + 1, count, stage.id.c_str(),
                  stageStatusName(stage.status), stage.seconds);
    line("[" + item.id + "] " + text);
}

void BatchProgress::itemEnd(const BatchItemResult& result) {
    if (result.status == BatchItemStatus::UpToDate)
        line(result.id + ": skipped: up to date");
    else if (result.status == BatchItemStatus::Ok)
        line(result.id + ": ok (" + std::to_string(result.stages->ran) + " ran, " +
             std::to_string(result.stages->cached) + " cached)");
    else
        line(result.id + ": failed: " + result.error, true);
    nlohmann::json end = {
        {"item", result.id}, {"status", batchItemStatusName(result.status)}, {"seconds", result.seconds}};
    if (result.status == BatchItemStatus::Failed) end["error"] = result.error;
    event("item-end", end);
}

void BatchProgress::done(const BatchSummary& summary) {
    event("done", {{"summary", batchSummaryJson(summary)}});
}

} // namespace ibl
