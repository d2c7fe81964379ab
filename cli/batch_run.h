// `iblbake batch MANIFEST` (README "Batch"): bake every item of a batch manifest in this shard, --jobs at a
// time, skipping items whose bake is already complete; a JSON summary is rewritten atomically after every
// item so a scheduler (or a person) can watch it. Shared by the engine, which bakes, and the front end
// (front_end.cpp), which answers a batch whose items are all up to date without loading the engine.
#pragma once

#include "bake_options.h"

#include <iblbake/bake_scene.h>
#include <iblbake/batch.h>

#include <CLI/CLI.hpp>

#include <filesystem>
#include <functional>
#include <map>
#include <string>

namespace ibl::cli {

struct BatchCommandOptions : BakeRunOptions {
    std::string manifest;
    int jobs = 1;
    std::string shard;
    int shardCount = 0; // 0: not given
    std::string summary;
};

// Adds the `batch` subcommand, bound to `options` (which must outlive `app`'s parse).
CLI::App* addBatchSubcommand(CLI::App& app, BatchCommandOptions& options);

// --shard, else the scheduler's job-array variables, else the whole manifest.
Shard chooseShard(const BatchCommandOptions& options);
// --summary, else <manifest dir>/batch-summary.json (batch-summary-K-of-N.json when sharded).
std::filesystem::path summaryPathFor(const BatchCommandOptions& options, const Shard& shard);

// How an item found stale (its check given) is baked: bakeStaleScene in the engine.
using BakeFunction =
    std::function<BakeSummary(const Scene&, const BakeOptions&, ProgressSink&, const UpToDate& checked)>;
// Up-to-date checks already made, by item index: taken instead of checking the item again.
using KnownUpToDate = std::map<std::size_t, UpToDate>;

// Runs the shard's items, prints the summary line and returns 0; throws ibl::Error when an item failed
// (the others completed) or the summary cannot be written.
int runBatch(const BatchCommandOptions& options, const BatchManifest& manifest, const Shard& shard,
             const BakeFunction& bake, const KnownUpToDate& known = {});

} // namespace ibl::cli
