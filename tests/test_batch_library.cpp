// Batch runs in-process (iblbake/batch_run/batch_run.h) on three tiny items (16-texel faces, draft, CPU
// backend): the summary the run returns, the file it leaves and what the observer sees; a second run skips
// finished items and bakes only the one that failed; shards, failed bakes as one line, and an unwritable
// summary. tests/test_batch.cpp runs `iblbake batch` end to end.
#include "cli_runner.h"
#include "scene_test_support.h"

#include <iblbake/baker/bake_scene.h>
#include <iblbake/batch_run/batch_run.h>
#include <iblbake/core/error.h>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <atomic>
#include <mutex>
#include <stdexcept>

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

// A manifest of a scene item and two HDRI items, each with its own input, outputs under out/.
struct BatchDir {
    fs::path dir;
    ibl::BatchManifest manifest;

    explicit BatchDir(const std::string& name) : dir(ibl::test::freshTempDir(name)) {
        json items = json::array();
        for (int i = 0; i < 3; ++i)
            ibl::test::writeLatLong(dir / ("env" + std::to_string(i) + ".hdr"), 0.25f * float(i + 1));
        const json scene = {{"environment", {{"file", "env0.hdr"}}},
                            {"outputs", {{"directory", "out/a"}, {"quality", "draft"}, {"faceSize", 16}}}};
        ibl::test::writeText(dir / "a.json", scene.dump());
        items.push_back({{"scene", "a.json"}, {"id", "a"}});
        for (const char* id : {"b", "c"})
            items.push_back({{"hdri", std::string("env") + (id[0] == 'b' ? "1" : "2") + ".hdr"},
                             {"id", id},
                             {"output", std::string("out/") + id},
                             {"preset", "draft"},
                             {"faceSize", 16}});
        manifest = ibl::parseBatchManifest(json{{"items", items}}.dump(), "batch.json", dir);
    }
    ~BatchDir() { fs::remove_all(dir); }

    ibl::BatchRunOptions options(int jobs = 1) const {
        ibl::BatchRunOptions o;
        o.bake.backend = ibl::Backend::Cpu;
        o.jobs = jobs;
        o.summaryFile = dir / "summary.json";
        return o;
    }
    json summaryFile() const { return json::parse(ibl::test::readBytes(dir / "summary.json")); }
};

// Records what the run reports; on each item's end, what the summary file says of the item then.
struct Recorder : ibl::BatchObserver {
    fs::path summaryFile;
    std::mutex mutex;
    int starts = 0, itemStarts = 0, stageStarts = 0, stageEnds = 0, dones = 0;
    std::vector<std::string> ended, statusInFileAtEnd;

    void batchStart(const ibl::BatchSummary&, const fs::path& file) override {
        summaryFile = file;
        ++starts;
    }
    void itemStart(const ibl::BatchItem&) override {
        std::lock_guard lock(mutex);
        ++itemStarts;
    }
    void stageStart(const ibl::BatchItem&, const ibl::StageResult&, int, int) override {
        std::lock_guard lock(mutex);
        ++stageStarts;
    }
    void stageEnd(const ibl::BatchItem&, const ibl::StageResult&, int, int) override {
        std::lock_guard lock(mutex);
        ++stageEnds;
    }
    void itemEnd(const ibl::BatchItemResult& result) override {
        std::lock_guard lock(mutex);
        ended.push_back(result.id);
        const json file = json::parse(ibl::test::readBytes(summaryFile));
        statusInFileAtEnd.push_back(file["items"][result.index]["status"]);
    }
    void done(const ibl::BatchSummary&) override { ++dones; }
};

const ibl::BatchItemResult& item(const ibl::BatchSummary& summary, const std::string& id) {
    for (const ibl::BatchItemResult& result : summary.items)
        if (result.id == id) return result;
    throw std::runtime_error("no item " + id);
}

// A bake that must not happen.
ibl::BakeSummary noBake(const ibl::Scene&, const ibl::BakeOptions&, ibl::ProgressSink&,
                        const ibl::UpToDate&) {
    throw std::logic_error("asked to bake");
}

TEST(BatchLibrary, BakesEveryItemAndTheSummaryFileIsTheReturnedSummary) {
    BatchDir d("batch_library_all");
    Recorder recorder;
    const ibl::BatchSummary summary =
        ibl::runBatch(d.manifest, ibl::Shard{}, d.options(2), ibl::bakeStaleScene, recorder);
    EXPECT_TRUE(summary.complete);
    EXPECT_TRUE(summary.ok);
    EXPECT_EQ(summary.count(ibl::BatchItemStatus::Ok), 3u);
    EXPECT_EQ(summary.jobs, 2);
    EXPECT_EQ(summary.manifest, "batch.json");
    int stagesRun = 0;
    for (const ibl::BatchItemResult& result : summary.items) {
        EXPECT_EQ(result.status, ibl::BatchItemStatus::Ok) << result.id << ": " << result.error;
        EXPECT_EQ(result.isScene, result.id == "a");
        EXPECT_EQ(result.output, d.dir / "out" / result.id);
        ASSERT_TRUE(result.stages) << result.id;
        EXPECT_GT(result.stages->ran, 0u);
        EXPECT_EQ(result.stages->upToDate, 0u);
        EXPECT_EQ(result.backend, "cpu");
        ASSERT_FALSE(result.products.empty());
        EXPECT_EQ(result.products.back().filename(), "manifest.json");
        for (const fs::path& product : result.products)
            EXPECT_TRUE(fs::is_regular_file(product)) << product;
        EXPECT_GT(result.seconds, 0.0);
        stagesRun += int(result.stages->ran + result.stages->cached);
    }
    // The file holds exactly the returned summary.
    EXPECT_EQ(d.summaryFile(), ibl::batchSummaryJson(summary));
    const json file = d.summaryFile();
    EXPECT_EQ(file["schema"], "iblbake.batch-summary");
    EXPECT_EQ(file["counts"],
              (json{{"ok", 3}, {"failed", 0}, {"up-to-date", 0}, {"not-in-shard", 0}, {"pending", 0}}));
    EXPECT_EQ(file["items"][1]["kind"], "hdri");
    EXPECT_FALSE(file["items"][1].contains("error"));
    // Every call once, and each item's end only once the file records it.
    EXPECT_EQ(recorder.starts, 1);
    EXPECT_EQ(recorder.dones, 1);
    EXPECT_EQ(recorder.itemStarts, 3);
    EXPECT_EQ(recorder.stageStarts, stagesRun);
    EXPECT_EQ(recorder.stageEnds, stagesRun);
    EXPECT_EQ(recorder.ended.size(), 3u);
    EXPECT_EQ(recorder.statusInFileAtEnd, std::vector<std::string>(3, "ok"));
}

// A run whose item b failed, run again: a and c are found up to date (not baked again, their products
// unchanged), only b is baked.
TEST(BatchLibrary, RunAgainBakesOnlyWhatDidNotFinish) {
    BatchDir d("batch_library_resume");
    ibl::BatchObserver quiet;
    const auto failOnB = [](const ibl::Scene& scene, const ibl::BakeOptions& options, ibl::ProgressSink& sink,
                            const ibl::UpToDate& checked) {
        if (scene.outputs.directory.filename() == "b") throw std::runtime_error("killed\nwhile baking b");
        return ibl::bakeStaleScene(scene, options, sink, checked);
    };
    const ibl::BatchSummary first = ibl::runBatch(d.manifest, ibl::Shard{}, d.options(), failOnB, quiet);
    EXPECT_FALSE(first.ok);
    EXPECT_EQ(item(first, "b").status, ibl::BatchItemStatus::Failed);
    EXPECT_EQ(item(first, "b").error, "killed while baking b"); // one line
    EXPECT_FALSE(item(first, "b").stages);
    EXPECT_FALSE(d.summaryFile()["items"][1].contains("products"));
    const std::string manifestOfA = ibl::test::readBytes(d.dir / "out" / "a" / "manifest.json");

    std::atomic<int> bakes{0};
    const auto counting = [&](const ibl::Scene& scene, const ibl::BakeOptions& options,
                              ibl::ProgressSink& sink, const ibl::UpToDate& checked) {
        ++bakes;
        return ibl::bakeStaleScene(scene, options, sink, checked);
    };
    const ibl::BatchSummary second = ibl::runBatch(d.manifest, ibl::Shard{}, d.options(2), counting, quiet);
    EXPECT_TRUE(second.ok);
    EXPECT_EQ(bakes, 1);
    EXPECT_EQ(item(second, "b").status, ibl::BatchItemStatus::Ok);
    for (const char* id : {"a", "c"}) {
        const ibl::BatchItemResult& result = item(second, id);
        EXPECT_EQ(result.status, ibl::BatchItemStatus::UpToDate) << id;
        ASSERT_TRUE(result.stages);
        EXPECT_EQ(result.stages->ran, 0u);
        EXPECT_GT(result.stages->upToDate, 0u);
        EXPECT_FALSE(result.backend) << id;
        EXPECT_EQ(result.products, item(first, id).products) << id;
    }
    EXPECT_EQ(ibl::test::readBytes(d.dir / "out" / "a" / "manifest.json"), manifestOfA);
    EXPECT_EQ(d.summaryFile()["counts"]["up-to-date"], 2);

    // Checks made before (the front end's) are taken as they are: nothing is checked or baked again.
    ibl::KnownUpToDate known;
    for (const ibl::BatchItem& i : d.manifest.items)
        known.emplace(i.index, ibl::checkBakeUpToDate(ibl::batchItemScene(d.manifest, i), d.options().bake));
    const ibl::BatchSummary third =
        ibl::runBatch(d.manifest, ibl::Shard{}, d.options(), noBake, quiet, known);
    EXPECT_EQ(third.count(ibl::BatchItemStatus::UpToDate), 3u);
}

// Shard 2/2 takes the item of index 1 only; a bake that reports failure fails the item with one line, its
// backend and products kept.
TEST(BatchLibrary, ShardTakesItsItemsAndAFailedBakeIsOneLine) {
    BatchDir d("batch_library_shard");
    ibl::BatchObserver quiet;
    const auto failing = [](const ibl::Scene&, const ibl::BakeOptions&, ibl::ProgressSink&,
                            const ibl::UpToDate&) {
        ibl::BakeSummary bake;
        bake.error = "stage specular:\nout of memory";
        bake.backend = "cpu";
        return bake;
    };
    const ibl::Shard shard = ibl::parseShard("2/2");
    const ibl::BatchSummary summary = ibl::runBatch(d.manifest, shard, d.options(), failing, quiet);
    EXPECT_TRUE(summary.complete);
    EXPECT_FALSE(summary.ok);
    EXPECT_EQ(item(summary, "a").status, ibl::BatchItemStatus::NotInShard);
    EXPECT_EQ(item(summary, "c").status, ibl::BatchItemStatus::NotInShard);
    EXPECT_EQ(item(summary, "b").status, ibl::BatchItemStatus::Failed);
    EXPECT_EQ(item(summary, "b").error, "stage specular: out of memory");
    const json file = d.summaryFile();
    EXPECT_EQ(file["shard"], (json{{"index", 2}, {"count", 2}, {"source", "--shard"}}));
    EXPECT_EQ(file["counts"]["not-in-shard"], 2);
    EXPECT_EQ(file["items"][0],
              (json{{"id", "a"}, {"index", 0}, {"kind", "scene"}, {"status", "not-in-shard"}}));
    EXPECT_EQ(file["items"][1]["backend"], "cpu");
    EXPECT_EQ(file["items"][1]["error"], "stage specular: out of memory");
    EXPECT_EQ(ibl::defaultBatchSummaryFile(d.dir / "batch.json", shard), d.dir / "batch-summary-2-of-2.json");
    EXPECT_EQ(ibl::defaultBatchSummaryFile(d.dir / "batch.json", ibl::Shard{}), d.dir / "batch-summary.json");
}

TEST(BatchLibrary, UnwritableSummaryStopsTheBatch) {
    BatchDir d("batch_library_unwritable");
    ibl::BatchObserver quiet;
    ibl::BatchRunOptions options = d.options();
    options.summaryFile = d.dir / "missing" / "summary.json";
    EXPECT_THROW(ibl::runBatch(d.manifest, ibl::Shard{}, options, noBake, quiet), ibl::Error);
    EXPECT_FALSE(fs::exists(d.dir / "out"));
}

} // namespace
