// Batch runs (docs/batch.md "Batch"): every item of a batch manifest in a shard baked, `jobs` at a time,
// items whose bake is already complete skipped (so a killed batch, run again, resumes without redoing
// finished items), and a JSON summary (schema iblbake.batch-summary) rewritten atomically after every item so
// a scheduler (or a person) can watch it. Free of OpenImageIO and OpenCL: the caller supplies how a stale
// item is baked, so the engine bakes with bakeStaleScene and the front end (cli/front_end.cpp), which links
// no backend, answers a batch whose items are all up to date.
#pragma once

#include "iblbake/bake_state/bake_state.h"
#include "iblbake/batch/batch.h"

#include <cstddef>
#include <filesystem>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace ibl {

enum class BatchItemStatus { Pending, NotInShard, Ok, Failed, UpToDate };
const char*
batchItemStatusName(BatchItemStatus status); // "pending", "not-in-shard", "ok", "failed", "up-to-date"

struct BatchItemStages {
    std::size_t ran = 0, cached = 0, upToDate = 0, skipped = 0;
};

// What became of one item: the summary's per-item object.
struct BatchItemResult {
    std::string id;
    std::size_t index = 0;
    bool isScene = false; // else an HDRI item
    BatchItemStatus status = BatchItemStatus::Pending;
    std::filesystem::path output; // once the item's scene loaded ("" before, or when it could not load)
    // Once the item was found up to date or its bake returned: its stage counts and products.
    std::optional<BatchItemStages> stages;
    std::vector<std::filesystem::path> products;
    std::optional<std::string> backend; // when it was baked
    std::string error;                  // one line, when Failed
    double seconds = 0.0;               // when finished (Ok, Failed or UpToDate)
};

struct BatchSummary {
    std::string manifest; // as the user named it
    Shard shard;
    int jobs = 1;
    bool complete = false; // every item of the shard finished
    bool ok = false;       // complete and none failed
    double seconds = 0.0;
    std::vector<BatchItemResult> items; // every item of the manifest, in manifest order
    std::size_t count(BatchItemStatus status) const;
};

// The summary file's document: {schema: "iblbake.batch-summary", schemaVersion: 1, manifest, shard, jobs,
// complete, ok, seconds, counts: {ok, failed, up-to-date, not-in-shard, pending}, items: [{id, index, kind:
// "scene"/"hdri", status, output, products, backend, stages: {ran, cached, upToDate, skipped}, error,
// seconds}]}, an item's keys present as BatchItemResult says.
nlohmann::json batchSummaryJson(const BatchSummary& summary);
nlohmann::json batchShardJson(const Shard& shard); // {index (1-based), count, source}

// <manifest dir>/batch-summary.json, or batch-summary-K-of-N.json when the shard is one of several.
std::filesystem::path defaultBatchSummaryFile(const std::filesystem::path& manifestFile, const Shard& shard);

// How an item found stale (its check given) is baked: bakeStaleScene in the engine.
using BatchBakeFunction =
    std::function<BakeSummary(const Scene&, const BakeOptions&, ProgressSink&, const UpToDate& checked)>;
// Up-to-date checks already made, by item index: taken instead of checking the item again.
using KnownUpToDate = std::map<std::size_t, UpToDate>;
// Every item of the shard checked, when all of them are up to date (runBatch then bakes none); nullopt at
// the first stale one. Throws what batchItemScene and checkBakeUpToDate throw.
std::optional<KnownUpToDate> shardUpToDate(const BatchManifest& manifest, const Shard& shard,
                                           const BakeOptions& options);

// What a batch reports as it runs; the defaults do nothing. The item calls come from the worker threads,
// for several items at once.
class BatchObserver {
  public:
    virtual ~BatchObserver() = default;
    // The summary as first written (the shard's items pending, the others not in the shard).
    virtual void batchStart(const BatchSummary& summary, const std::filesystem::path& summaryFile) {}
    virtual void itemStart(const BatchItem& item) {}
    virtual void stageStart(const BatchItem& item, const StageResult& stage, int index, int count) {}
    virtual void stageEnd(const BatchItem& item, const StageResult& stage, int index, int count) {}
    // Once the summary file records the item (one call at a time, in the order the file records them).
    virtual void itemEnd(const BatchItemResult& result) {}
    virtual void done(const BatchSummary& summary) {}
};

struct BatchRunOptions {
    BakeOptions bake;
    int jobs = 1; // items baked in parallel, each bake with its own Executor (OpenCL context and queue)
    std::filesystem::path summaryFile;
};

// Runs the shard's items and returns the complete summary (ok = false when an item failed; the others
// completed). Throws ibl::Error when the summary file cannot be written (then no further item starts).
BatchSummary runBatch(const BatchManifest& manifest, const Shard& shard, const BatchRunOptions& options,
                      const BatchBakeFunction& bake, BatchObserver& observer,
                      const KnownUpToDate& known = {});

} // namespace ibl
