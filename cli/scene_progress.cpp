#include "scene_progress.h"

#include <nlohmann/json.hpp>

#include <cstdio>
#include <string>
#include <unistd.h>

namespace ibl::cli {

ProgressMode chooseProgressMode(bool quiet, bool json) {
    if (json) return ProgressMode::Json;
    if (quiet) return ProgressMode::Quiet;
    return ::isatty(STDERR_FILENO) ? ProgressMode::Bar : ProgressMode::Lines;
}

void ConsoleProgress::stageStart(const StageResult& stage, int index, int count) {
    if (mode_ == ProgressMode::Json) {
        std::printf("%s\n", nlohmann::json{{"event", "stage-start"},
                                           {"stage", stage.id},
                                           {"kind", stage.kind},
                                           {"index", index},
                                           {"count", count}}
                                .dump()
                                .c_str());
        std::fflush(stdout);
    } else if (mode_ == ProgressMode::Bar) {
        // ETA: the mean time of the stages done so far times the stages left (a rough guide).
        const double elapsed =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
        std::string eta =
            index > 0 ? " ETA " + std::to_string(int(elapsed / index * (count - index) + 0.5)) + " s" : "";
        constexpr int kWidth = 20;
        const int filled = kWidth * index / count;
        std::fprintf(stderr, "\r\033[K[%s%s] %d/%d %s%s", std::string(std::size_t(filled), '#').c_str(),
                     std::string(std::size_t(kWidth - filled), '.').c_str(), index, count, stage.id.c_str(),
                     eta.c_str());
        std::fflush(stderr);
        barDrawn_ = true;
    }
}

void ConsoleProgress::stageEnd(const StageResult& stage, int index, int count) {
    if (mode_ == ProgressMode::Json) {
        std::printf("%s\n", nlohmann::json{{"event", "stage-end"},
                                           {"stage", stage.id},
                                           {"status", stageStatusName(stage.status)},
                                           {"cached", stage.status == StageStatus::Cached},
                                           {"seconds", stage.seconds}}
                                .dump()
                                .c_str());
        std::fflush(stdout);
    } else if (mode_ == ProgressMode::Lines) {
        std::fprintf(stderr, "[%d/%d] %-20s %-7s %.2f s\n", index + 1, count, stage.id.c_str(),
                     stageStatusName(stage.status), stage.seconds);
    }
}

void ConsoleProgress::done(const BakeSummary& summary) {
    if (barDrawn_) std::fprintf(stderr, "\r\033[K");
    if (mode_ == ProgressMode::Json) {
        std::printf("%s\n",
                    nlohmann::json{{"event", "done"}, {"summary", bakeSummaryJson(summary)}}.dump().c_str());
    } else if (mode_ != ProgressMode::Quiet && summary.ok) {
        std::printf("baked %zu stages (%d ran, %d cached, %zu skipped) in %.2f s (%s) -> %s\n",
                    summary.stages.size(), summary.ran(), summary.cached(), summary.skipped.size(),
                    summary.seconds, summary.backend.c_str(), summary.manifest.string().c_str());
        // Products stored scaled or clamped on request (DESIGN.md "Float storage"); unscaled ones say
        // nothing.
        for (const StoredProduct& p : summary.storage)
            if (p.clamped || p.storageScale != 1.0) std::printf("storage %s\n", storageLine(p).c_str());
    }
    std::fflush(stdout);
}

} // namespace ibl::cli
