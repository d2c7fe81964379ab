#include "batch_options.h"

#include <iblbake/batch_run/batch_progress.h>
#include <iblbake/core/error.h>

#include <cstdio>
#include <cstdlib>
#include <optional>

namespace ibl::cli {

CLI::App* addBatchSubcommand(CLI::App& app, BatchCommandOptions& o) {
    CLI::App* cmd = app.add_subcommand("batch", "bake every item of a batch manifest (build farms: --shard)");
    cmd->add_option("manifest", o.manifest, "batch manifest (JSON, docs/batch.md \"Batch\")")->required();
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

int runBatchCommand(const BatchCommandOptions& o, const BatchManifest& manifest, const Shard& shard,
                    const BatchBakeFunction& bake, const KnownUpToDate& known) {
    BatchRunOptions run;
    run.bake = o.bakeOptions();
    run.jobs = o.jobs;
    run.summaryFile =
        o.summary.empty() ? defaultBatchSummaryFile(o.manifest, shard) : std::filesystem::path(o.summary);
    BatchProgress progress(chooseProgressMode(o.quiet, o.json));
    const BatchSummary summary = runBatch(manifest, shard, run, bake, progress, known);
    if (!o.json && !o.quiet) {
        std::printf("batch: %zu ok, %zu up to date, %zu failed, %zu not in shard in %.2f s -> %s\n",
                    summary.count(BatchItemStatus::Ok), summary.count(BatchItemStatus::UpToDate),
                    summary.count(BatchItemStatus::Failed), summary.count(BatchItemStatus::NotInShard),
                    summary.seconds, run.summaryFile.string().c_str());
        std::fflush(stdout);
    }
    if (const std::size_t failed = summary.count(BatchItemStatus::Failed))
        throw Error(std::to_string(failed) + " of " + std::to_string(manifest.items.size()) +
                    " items failed (see " + run.summaryFile.string() + ")");
    return 0;
}

} // namespace ibl::cli
