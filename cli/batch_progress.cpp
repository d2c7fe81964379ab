#include "batch_progress.h"

#include <cstdio>

namespace ibl::cli {

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

void ItemProgress::stageStart(const StageResult& stage, int index, int count) {
    batch_.event(
        "stage-start",
        {{"item", item_}, {"stage", stage.id}, {"kind", stage.kind}, {"index", index}, {"count", count}});
}

void ItemProgress::stageEnd(const StageResult& stage, int index, int count) {
    batch_.event("stage-end", {{"item", item_},
                               {"stage", stage.id},
                               {"status", stageStatusName(stage.status)},
                               {"cached", stage.status == StageStatus::Cached},
                               {"seconds", stage.seconds}});
    char text[160];
    std::snprintf(text, sizeof text, "%d/%d %-20s %-7s %.2f s", index + 1, count, stage.id.c_str(),
                  stageStatusName(stage.status), stage.seconds);
    batch_.line("[" + item_ + "] " + text);
}

} // namespace ibl::cli
