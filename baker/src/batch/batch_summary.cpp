// The batch summary's document and file name (iblbake/batch_run/batch_run.h).
#include "iblbake/batch_run/batch_run.h"

namespace ibl {

namespace {

using nlohmann::json;

json pathList(const std::vector<std::filesystem::path>& paths) {
    json out = json::array();
    for (const std::filesystem::path& p : paths)
        out.push_back(p.string());
    return out;
}

json itemJson(const BatchItemResult& item) {
    json out = {{"id", item.id},
                {"index", item.index},
                {"kind", item.isScene ? "scene" : "hdri"},
                {"status", batchItemStatusName(item.status)}};
    if (!item.output.empty()) out["output"] = item.output.string();
    if (item.stages) {
        out["products"] = pathList(item.products);
        out["stages"] = {{"ran", item.stages->ran},
                         {"cached", item.stages->cached},
                         {"upToDate", item.stages->upToDate},
                         {"skipped", item.stages->skipped}};
    }
    if (item.backend) out["backend"] = *item.backend;
    if (item.status == BatchItemStatus::Failed) out["error"] = item.error;
    if (item.status != BatchItemStatus::Pending && item.status != BatchItemStatus::NotInShard)
        out["seconds"] = item.seconds;
    return out;
}

} // namespace

const char* batchItemStatusName(BatchItemStatus status) {
    switch (status) {
    case BatchItemStatus::Pending:
        return "pending";
    case BatchItemStatus::NotInShard:
        return "not-in-shard";
    case BatchItemStatus::Ok:
        return "ok";
    case BatchItemStatus::Failed:
        return "failed";
    case BatchItemStatus::UpToDate:
        return "up-to-date";
    }
    return "?";
}

std::size_t BatchSummary::count(BatchItemStatus status) const {
    std::size_t n = 0;
    for (const BatchItemResult& item : items)
        n += item.status == status;
    return n;
}

json batchShardJson(const Shard& shard) {
    return {{"index", shard.index + 1}, {"count", shard.count}, {"source", shard.source}};
}

json batchSummaryJson(const BatchSummary& summary) {
    json counts = json::object(), items = json::array();
    for (BatchItemStatus status : {BatchItemStatus::Ok, BatchItemStatus::Failed, BatchItemStatus::UpToDate,
                                   BatchItemStatus::NotInShard, BatchItemStatus::Pending})
        counts[batchItemStatusName(status)] = summary.count(status);
    for (const BatchItemResult& item : summary.items)
        items.push_back(itemJson(item));
    return {{"schema", "iblbake.batch-summary"},
            {"schemaVersion", 1},
            {"manifest", summary.manifest},
            {"shard", batchShardJson(summary.shard)},
            {"jobs", summary.jobs},
            {"complete", summary.complete},
            {"ok", summary.ok},
            {"seconds", summary.seconds},
            {"counts", counts},
            {"items", items}};
}

std::filesystem::path defaultBatchSummaryFile(const std::filesystem::path& manifestFile, const Shard& shard) {
    const std::filesystem::path base = manifestFile.parent_path();
    if (shard.count == 1) return base / "batch-summary.json";
    return base / ("batch-summary-" + std::to_string(shard.index + 1) + "-of-" + std::to_string(shard.count) +
                   ".json");
}

} // namespace ibl
