// The batch run behind `iblbake batch MANIFEST` (batch_run.h), shared by the engine and the front end.
#include "batch_run.h"

#include "batch_progress.h"

#include <iblbake/atomic_file.h>
#include <iblbake/error.h>

#include <atomic>
#include <chrono>
#include <cstdlib>
#include <exception>
#include <fstream>
#include <mutex>
#include <optional>
#include <thread>

namespace ibl::cli {

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

double secondsSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

json pathList(const std::vector<fs::path>& paths) {
    json out = json::array();
    for (const fs::path& p : paths)
        out.push_back(p.string());
    return out;
}

// What became of one item; the summary's per-item object.
json itemJson(const BatchItem& item, const std::string& status) {
    return {{"id", item.id},
            {"index", item.index},
            {"kind", item.isScene() ? "scene" : "hdri"},
            {"status", status}};
}

// One line: an error message may span lines (a library's), the summary's `error` must not.
std::string oneLine(std::string text) {
    for (char& c : text)
        if (c == '\n' || c == '\r') c = ' ';
    return text;
}

class BatchRun {
  public:
    BatchRun(const BatchManifest& manifest, const Shard& shard, const BakeOptions& options,
             fs::path summaryPath, BatchProgress& progress, int jobs, const BakeFunction& bake,
             const KnownUpToDate& known)
        : manifest_(manifest), shard_(shard), options_(options), summaryPath_(std::move(summaryPath)),
          progress_(progress), jobs_(jobs), bake_(bake), known_(known) {
        for (const BatchItem& item : manifest.items)
            items_.push_back(itemJson(item, inShard(item, shard) ? "pending" : "not-in-shard"));
    }

    // Runs every item of the shard; returns how many failed.
    int run() {
        std::vector<std::size_t> mine;
        for (const BatchItem& item : manifest_.items)
            if (inShard(item, shard_)) mine.push_back(item.index);
        progress_.event("batch-start", {{"items", manifest_.items.size()},
                                        {"inShard", mine.size()},
                                        {"shard", shardJson()},
                                        {"jobs", jobs_},
                                        {"summary", summaryPath_.string()}});
        writeSummary(false);
        // One bake per worker at a time; each bakeScene makes its own Executor (its own OpenCL context and
        // queue), so parallel items share no OpenCL objects.
        std::atomic<std::size_t> next{0};
        std::exception_ptr summaryFailure; // the summary file became unwritable: stop taking items
        auto worker = [&] {
            try {
                for (std::size_t i; (i = next++) < mine.size();)
                    runItem(manifest_.items[mine[i]]);
            } catch (...) {
                next = mine.size();
                std::lock_guard lock(mutex_);
                if (!summaryFailure) summaryFailure = std::current_exception();
            }
        };
        std::vector<std::thread> threads;
        for (int t = 1; t < std::min<int>(jobs_, int(mine.size())); ++t)
            threads.emplace_back(worker);
        worker();
        for (std::thread& t : threads)
            t.join();
        if (summaryFailure) std::rethrow_exception(summaryFailure);
        writeSummary(true);
        progress_.event("done", {{"summary", summaryJson(true)}});
        return failed_;
    }

    json summaryJson(bool complete) const {
        json counts = {{"ok", 0}, {"failed", 0}, {"up-to-date", 0}, {"not-in-shard", 0}, {"pending", 0}};
        for (const json& item : items_)
            counts[item["status"].get<std::string>()] =
                counts[item["status"].get<std::string>()].get<int>() + 1;
        return {{"schema", "iblbake.batch-summary"},
                {"schemaVersion", 1},
                {"manifest", manifest_.name},
                {"shard", shardJson()},
                {"jobs", jobs_},
                {"complete", complete},
                {"ok", complete && failed_ == 0},
                {"seconds", secondsSince(start_)},
                {"counts", counts},
                {"items", items_}};
    }

  private:
    json shardJson() const {
        return {{"index", shard_.index + 1}, {"count", shard_.count}, {"source", shard_.source}};
    }

    void runItem(const BatchItem& item) {
        const auto start = std::chrono::steady_clock::now();
        progress_.event("item-start", {{"item", item.id}, {"index", item.index}});
        json result = itemJson(item, "failed");
        try {
            const Scene scene = batchItemScene(manifest_, item);
            result["output"] = scene.outputs.directory.string();
            const Plan plan = planScene(scene);
            const auto known = known_.find(item.index);
            const UpToDate upToDate =
                known != known_.end() ? known->second : checkBakeUpToDate(scene, options_);
            if (upToDate.upToDate) {
                result["status"] = "up-to-date";
                result["products"] = pathList(upToDate.products);
                result["stages"] = {{"ran", 0},
                                    {"cached", 0},
                                    {"upToDate", plan.stages.size()},
                                    {"skipped", plan.skipped.size()}};
                progress_.line(item.id + ": skipped: up to date");
            } else {
                ItemProgress sink(progress_, item.id);
                const BakeSummary bake = bake_(scene, options_, sink, upToDate);
                result["status"] = bake.ok ? "ok" : "failed";
                result["products"] = pathList(bake.products);
                result["backend"] = bake.backend;
                result["stages"] = {{"ran", bake.ran()},
                                    {"cached", bake.cached()},
                                    {"upToDate", 0},
                                    {"skipped", bake.skipped.size()}};
                if (!bake.ok) result["error"] = oneLine(bake.error);
            }
        } catch (const std::exception& e) { // the scene file cannot be read or is invalid
            result["error"] = oneLine(e.what());
        }
        result["seconds"] = secondsSince(start);
        const std::string status = result["status"];
        if (status == "ok")
            progress_.line(item.id + ": ok (" + std::to_string(result["stages"]["ran"].get<int>()) +
                           " ran, " + std::to_string(result["stages"]["cached"].get<int>()) + " cached)");
        else if (status == "failed")
            progress_.line(item.id + ": failed: " + result["error"].get<std::string>(), true);
        json end = {{"item", item.id}, {"status", status}, {"seconds", result["seconds"]}};
        if (result.contains("error")) end["error"] = result["error"];
        std::lock_guard lock(mutex_);
        failed_ += status == "failed";
        items_[item.index] = std::move(result);
        writeSummaryLocked(false);
        progress_.event("item-end",
                        end); // after the summary: a watcher that sees it finds the summary current
    }

    void writeSummary(bool complete) {
        std::lock_guard lock(mutex_);
        writeSummaryLocked(complete);
    }

    void writeSummaryLocked(bool complete) const {
        AtomicFile file(summaryPath_);
        std::ofstream out(file.tempPath());
        out << summaryJson(complete).dump(2) << '\n';
        out.close();
        if (!out) throw Error(summaryPath_.string() + ": cannot write");
        file.commit();
    }

    const BatchManifest& manifest_;
    const Shard shard_;
    const BakeOptions& options_;
    const fs::path summaryPath_;
    BatchProgress& progress_;
    const int jobs_;
    const BakeFunction& bake_;
    const KnownUpToDate& known_;
    const std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
    std::mutex mutex_; // guards items_, failed_ and the summary file
    std::vector<json> items_;
    int failed_ = 0;
};

} // namespace

CLI::App* addBatchSubcommand(CLI::App& app, BatchCommandOptions& o) {
    CLI::App* cmd = app.add_subcommand("batch", "bake every item of a batch manifest (build farms: --shard)");
    cmd->add_option("manifest", o.manifest, "batch manifest (JSON, README \"Batch\")")->required();
    cmd->add_option("--jobs,-j", o.jobs, "items baked in parallel (each with its own OpenCL context)")
        ->check(CLI::Range(1, 256));
    cmd->add_option("--shard", o.shard,
                    "K/N: bake only items whose manifest index i has i mod N = K-1 (default: from "
                    "SLURM_ARRAY_TASK_* or JOB_COMPLETION_INDEX, else all)");
    cmd->add_option("--shard-count", o.shardCount,
                    "shard count with JOB_COMPLETION_INDEX (else $IBLBAKE_SHARD_COUNT)")
        ->check(CLI::Range(1, 1000000));
    cmd->add_option("--summary", o.summary,
                    "JSON summary (default: <manifest dir>/batch-summary.json, batch-summary-K-of-N.json "
                    "when sharded)");
    o.addTo(*cmd, "recompute every stage of every item",
            "cache directory shared by every item (default: each output's own)");
    return cmd;
}

Shard chooseShard(const BatchCommandOptions& o) {
    if (!o.shard.empty()) return parseShard(o.shard);
    const std::optional<int> count = o.shardCount > 0 ? std::optional<int>(o.shardCount) : std::nullopt;
    if (auto shard = shardFromEnvironment([](const char* name) { return std::getenv(name); }, count))
        return *shard;
    if (count) throw Error("--shard-count: needs JOB_COMPLETION_INDEX (Kubernetes indexed job)");
    return Shard{};
}

fs::path summaryPathFor(const BatchCommandOptions& o, const Shard& shard) {
    if (!o.summary.empty()) return o.summary;
    const fs::path base = fs::path(o.manifest).parent_path();
    if (shard.count == 1) return base / "batch-summary.json";
    return base / ("batch-summary-" + std::to_string(shard.index + 1) + "-of-" + std::to_string(shard.count) +
                   ".json");
}

int runBatch(const BatchCommandOptions& o, const BatchManifest& manifest, const Shard& shard,
             const BakeFunction& bake, const KnownUpToDate& known) {
    const fs::path summaryPath = summaryPathFor(o, shard);
    BatchProgress progress(chooseProgressMode(o.quiet, o.json));
    const BakeOptions options = o.bakeOptions();
    BatchRun run(manifest, shard, options, summaryPath, progress, o.jobs, bake, known);
    const int failed = run.run();
    const json summary = run.summaryJson(true);
    if (!o.json && !o.quiet) {
        const json& c = summary["counts"];
        std::printf("batch: %d ok, %d up to date, %d failed, %d not in shard in %.2f s -> %s\n",
                    c["ok"].get<int>(), c["up-to-date"].get<int>(), c["failed"].get<int>(),
                    c["not-in-shard"].get<int>(), summary["seconds"].get<double>(),
                    summaryPath.string().c_str());
        std::fflush(stdout);
    }
    if (failed > 0)
        throw Error(std::to_string(failed) + " of " + std::to_string(manifest.items.size()) +
                    " items failed (see " + summaryPath.string() + ")");
    return 0;
}

} // namespace ibl::cli
