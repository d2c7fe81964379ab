#include "iblbake/bake_state/console_progress.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <unistd.h>

namespace ibl {

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
        barLine_ = "[" + std::string(std::size_t(filled), '#') +
                   std::string(std::size_t(kWidth - filled), '.') + "] " + std::to_string(index) + "/" +
                   std::to_string(count) + " " + stage.id;
        std::fprintf(stderr, "\r\033[K%s%s", barLine_.c_str(), eta.c_str());
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

namespace {

// "about 4 s more", or "" without an estimate.
std::string secondsLeftText(double secondsLeft) {
    if (secondsLeft < 0.0) return "";
    char text[48];
    std::snprintf(text, sizeof text, ", about %.0f s more", std::max(1.0, std::ceil(secondsLeft)));
    return text;
}

} // namespace

void ConsoleProgress::stageWaiting(const StageResult& stage, const std::string& what,
                                   const std::string& detail, double secondsLeft) {
    if (mode_ == ProgressMode::Json) {
        nlohmann::json event = {
            {"event", "stage-waiting"}, {"stage", stage.id}, {"on", what}, {"detail", detail}};
        if (secondsLeft >= 0.0) event["secondsLeft"] = secondsLeft;
        std::printf("%s\n", event.dump().c_str());
        std::fflush(stdout);
    } else if (mode_ == ProgressMode::Bar) {
        std::fprintf(stderr, "\r\033[K%s: %s (%s%s)", barLine_.c_str(), what.c_str(), detail.c_str(),
                     secondsLeftText(secondsLeft).c_str());
        std::fflush(stderr);
    } else if (mode_ == ProgressMode::Lines) {
        std::fprintf(stderr, "      %-20s waiting on %s: %s%s\n", stage.id.c_str(), what.c_str(),
                     detail.c_str(), secondsLeftText(secondsLeft).c_str());
    }
}

namespace {

std::string sizeText(std::uintmax_t bytes) {
    char text[32];
    if (bytes >= 1024 * 1024)
        std::snprintf(text, sizeof text, "%.1f MiB", double(bytes) / (1024.0 * 1024.0));
    else
        std::snprintf(text, sizeof text, "%.0f KiB", std::ceil(double(bytes) / 1024.0));
    return text;
}

// The bake's report (bake_state.h BakeSummary::report): one line per product, the calibration, the
// preview's error per roughness column, the manifest's warnings; one screen.
void printReport(const BakeSummary& summary) {
    std::size_t pathWidth = 4;
    for (const ProductReport& r : summary.report)
        pathWidth = std::max(pathWidth, r.path.string().size());
    for (const ProductReport& r : summary.report) {
        const std::string files = r.files > 1 ? " (" + std::to_string(r.files) + " files)" : "";
        std::printf("  %-16s %-*s %9s  %s%s\n", r.name.c_str(), int(pathWidth), r.path.string().c_str(),
                    sizeText(r.bytes).c_str(), r.description.c_str(), files.c_str());
    }
    if (!summary.calibration.empty()) std::printf("calibration %s\n", summary.calibration.c_str());
    for (const std::string& w : summary.warnings)
        std::printf("warning     %s\n", w.c_str());
    if (!summary.previewError) return;
    const PreviewErrorReport& e = *summary.previewError;
    std::printf("error       runtime vs brute-force reference (relative mean luminance), per roughness:\n");
    const auto row = [](const char* name, const std::vector<double>& values, double scale, const char* unit) {
        std::printf("  %-10s", name);
        for (double v : values)
            std::printf(" %5.1f%s", scale * v, unit);
        std::printf("\n");
    };
    row("roughness", e.roughness, 1.0, " ");
    row("dielectric", e.dielectric, 100.0, "%");
    row("metal", e.metal, 100.0, "%");
    row("reference", e.referenceError, 100.0, "%"); // its own estimated error
}

} // namespace

void ConsoleProgress::done(const BakeSummary& summary) {
    if (barDrawn_) std::fprintf(stderr, "\r\033[K");
    if (mode_ == ProgressMode::Json) {
        std::printf("%s\n",
                    nlohmann::json{{"event", "done"}, {"summary", bakeSummaryJson(summary)}}.dump().c_str());
    } else if (mode_ != ProgressMode::Quiet && summary.ok) {
        std::printf("baked %zu stages (%d ran, %d cached, %zu skipped) in %.2f s (%s) -> %s\n",
                    summary.stages.size(), summary.ran(), summary.cached(), summary.skipped.size(),
                    summary.seconds, summary.backend.c_str(), summary.manifest.string().c_str());
        printReport(summary);
        // Products stored scaled or clamped on request (docs/conventions.md "Float storage and the storage
        // scale"); unscaled ones say nothing.
        for (const StoredProduct& p : summary.storage)
            if (p.clamped || p.storageScale != 1.0) std::printf("storage %s\n", storageLine(p).c_str());
    }
    std::fflush(stdout);
}

} // namespace ibl
