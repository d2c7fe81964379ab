// runBatch (iblbake/batch_run/batch_run.h): the shard's items on `jobs` worker threads, the summary file
// rewritten after every item.
#include "iblbake/batch_run/batch_run.h"

#include "iblbake/core/error.h"
#include "iblbake/ktx2/atomic_file.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <exception>
#include <mutex>
#include <thread>

namespace ibl {

namespace {

namespace fs = std::filesystem;

double secondsSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// One line: an error message may span lines (a library's), the summary's `error` must not.
std::string oneLine(std::string text) {
    for (char& c : text)
        if (c == '\n' || c == '\r') c = ' ';
    return text;
}

// The sink one item's bake reports to: the observer's stage calls, naming the item.
class ItemStages : public ProgressSink {
  public:
    ItemStages(BatchObserver& observer, const BatchItem& item) : observer_(observer), item_(item) {}
    void stageStart(const StageResult& stage, int index, int count) override {
        observer_.stageStart(item_, stage, index, count);
    }
    void stageEnd(const StageResult& stage, int index, int count) override {
        observer_.stageEnd(item_, stage, index, count);
    }

  private:
    BatchObserver& observer_;
    const BatchItem& item_;
};

class BatchRun {
  public:
    BatchRun(const BatchManifest& manifest, const Shard& shard, const BatchRunOptions& options,
             const BatchBakeFunction& bake, BatchObserver& observer, const KnownUpToDate& known)
        : manifest_(manifest), shard_(shard), options_(options), bake_(bake), observer_(observer),
          known_(known), summaryTarget_(options.summaryFile) {
        // Below an output root the summary is confined as the items' outputs are: it must lie below the root,
        // and is written through its directory opened from the root without following links.
        if (!options.bake.outputRoot.empty()) try {
                root_.emplace(options.bake.outputRoot);
                const fs::path relative = root_->below(options.summaryFile);
                std::vector<fs::path> created;
                summaryTarget_ = root_->openDirectory(relative.parent_path(), created) / relative.filename();
            } catch (const OutputError& e) {
                throw OutputError(std::string("the batch summary: ") + e.what());
            }
        summary_.manifest = manifest.name;
        summary_.shard = shard;
        summary_.jobs = options.jobs;
        for (const BatchItem& item : manifest.items) {
            BatchItemResult result = startedResult(item);
            result.status = inShard(item, shard) ? BatchItemStatus::Pending : BatchItemStatus::NotInShard;
            summary_.items.push_back(std::move(result));
        }
    }

    BatchSummary run() {
        std::vector<std::size_t> mine;
        for (const BatchItem& item : manifest_.items)
            if (inShard(item, shard_)) mine.push_back(item.index);
        observer_.batchStart(summary_, options_.summaryFile);
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
        for (int t = 1; t < std::min<int>(options_.jobs, int(mine.size())); ++t)
            threads.emplace_back(worker);
        worker();
        for (std::thread& t : threads)
            t.join();
        if (summaryFailure) std::rethrow_exception(summaryFailure);
        writeSummary(true);
        observer_.done(summary_);
        return summary_;
    }

  private:
    static BatchItemResult startedResult(const BatchItem& item) {
        BatchItemResult result;
        result.id = item.id;
        result.index = item.index;
        result.isScene = item.isScene();
        return result;
    }

    void runItem(const BatchItem& item) {
        const auto start = std::chrono::steady_clock::now();
        observer_.itemStart(item);
        BatchItemResult result = startedResult(item);
        result.status = BatchItemStatus::Failed;
        try {
            const Scene scene = batchItemScene(manifest_, item);
            result.output = scene.outputs.directory;
            const Plan plan = planScene(scene);
            const auto known = known_.find(item.index);
            const UpToDate upToDate =
                known != known_.end() ? known->second : checkBakeUpToDate(scene, options_.bake);
            if (upToDate.upToDate) {
                result.status = BatchItemStatus::UpToDate;
                result.products = upToDate.products;
                result.stages = BatchItemStages{0, 0, plan.stages.size(), plan.skipped.size()};
            } else {
                ItemStages sink(observer_, item);
                const BakeSummary bake = bake_(scene, options_.bake, sink, upToDate);
                result.status = bake.ok ? BatchItemStatus::Ok : BatchItemStatus::Failed;
                result.products = bake.products;
                result.backend = bake.backend;
                result.stages = BatchItemStages{std::size_t(bake.ran()), std::size_t(bake.cached()), 0,
                                                bake.skipped.size()};
                if (!bake.ok) result.error = oneLine(bake.error);
            }
        } catch (const std::exception& e) { // the scene file cannot be read or is invalid
            result.error = oneLine(e.what());
        }
        result.seconds = secondsSince(start);
        std::lock_guard lock(mutex_);
        summary_.items[item.index] = std::move(result);
        writeSummaryLocked(false);
        observer_.itemEnd(summary_.items[item.index]); // after the summary: a watcher finds it current
    }

    void writeSummary(bool complete) {
        std::lock_guard lock(mutex_);
        writeSummaryLocked(complete);
    }

    void writeSummaryLocked(bool complete) {
        summary_.complete = complete;
        summary_.ok = complete && summary_.count(BatchItemStatus::Failed) == 0;
        summary_.seconds = secondsSince(start_);
        AtomicFile file(summaryTarget_);
        writeFileBytes(file.tempPath(), batchSummaryJson(summary_).dump(2) + '\n',
                       options_.summaryFile.string());
        file.commit();
    }

    const BatchManifest& manifest_;
    const Shard shard_;
    const BatchRunOptions& options_;
    const BatchBakeFunction& bake_;
    BatchObserver& observer_;
    const KnownUpToDate& known_;
    std::optional<OutputRoot> root_;
    fs::path summaryTarget_; // the summary file, or below an output root the path it is written through
    const std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
    std::mutex mutex_; // guards summary_ and the summary file
    BatchSummary summary_;
};

} // namespace

BatchSummary runBatch(const BatchManifest& manifest, const Shard& shard, const BatchRunOptions& options,
                      const BatchBakeFunction& bake, BatchObserver& observer, const KnownUpToDate& known) {
    return BatchRun(manifest, shard, options, bake, observer, known).run();
}

std::optional<KnownUpToDate> shardUpToDate(const BatchManifest& manifest, const Shard& shard,
                                           const BakeOptions& options) {
    KnownUpToDate known;
    for (const BatchItem& item : manifest.items) {
        if (!inShard(item, shard)) continue;
        UpToDate upToDate = checkBakeUpToDate(batchItemScene(manifest, item), options);
        if (!upToDate.upToDate) return std::nullopt;
        known.emplace(item.index, std::move(upToDate));
    }
    return known;
}

} // namespace ibl
