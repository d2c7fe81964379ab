// The command line of `iblbake batch MANIFEST` (docs/batch.md "Batch"), declared once: the engine's batch
// command bakes stale items with bakeStaleScene, the front end (front_end.cpp) answers a batch whose items
// are all up to date; both run it through the library's runBatch (iblbake/batch_run/batch_run.h).
#pragma once

#include "bake_options.h"

#include <iblbake/batch_run/batch_run.h>

#include <CLI/CLI.hpp>

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

// Runs the shard's items with progress as the options say, prints the summary line and returns 0; throws
// ibl::Error when an item failed (the others completed) or the summary cannot be written.
int runBatchCommand(const BatchCommandOptions& options, const BatchManifest& manifest, const Shard& shard,
                    const BatchBakeFunction& bake, const KnownUpToDate& known = {});

} // namespace ibl::cli
