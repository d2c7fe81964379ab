// Confined output for farms (issue 44, docs/scenes.md "Confined output"): below --output-root a scene writes
// only below the root once links are resolved, absolute output paths are refused, and a link placed or
// swapped in while the bake runs cannot redirect a write; each refusal is one line and leaves nothing.
#include "cli_runner.h"
#include "scene_test_support.h"

#include <iblbake/baker/bake_scene.h>
#include <iblbake/batch_run/batch_run.h>
#include <iblbake/core/error.h>
#include <iblbake/core/output_root.h>
#include <iblbake/scene/scene.h>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cstdlib>

namespace fs = std::filesystem;
using nlohmann::json;
using namespace ibl;
using namespace ibl::test;

namespace {

// Every file and directory below `dir`, relative, sorted.
std::vector<std::string> treeOf(const fs::path& dir) {
    std::vector<std::string> out;
    for (const fs::directory_entry& e : fs::recursive_directory_iterator(dir))
        out.push_back(fs::relative(e.path(), dir).string());
    std::sort(out.begin(), out.end());
    return out;
}

// A farm's layout: root/ (the output root) holding scenes/ with an HDRI, and outside/ beside the root.
struct Farm {
    fs::path dir, root, scenes, outside;
    explicit Farm(const std::string& name)
        : dir(freshTempDir(name)), root(dir / "root"), scenes(root / "scenes"), outside(dir / "outside") {
        fs::create_directories(scenes);
        fs::create_directories(outside);
        writeLatLong(scenes / "sky.exr", 0.4f);
    }
    ~Farm() { fs::remove_all(dir); }
    // A scene in scenes/ writing to `directory`, baked below the root (draft, 16-px faces, on the CPU).
    BakeSummary bake(const std::string& directory, ProgressSink& progress) const {
        writeText(scenes / "scene.json",
                  json{{"environment", {{"file", "sky.exr"}}},
                       {"outputs", {{"directory", directory}, {"quality", "draft"}, {"faceSize", 16}}}}
                      .dump());
        BakeOptions options;
        options.backend = Backend::Cpu;
        options.outputRoot = root;
        return bakeScene(loadSceneFile(scenes / "scene.json"), options, progress);
    }
    BakeSummary bake(const std::string& directory) const {
        ProgressSink silent;
        return bake(directory, silent);
    }
};

} // namespace

TEST(OutputRoot, PathsBelowTheRootAfterLinksAreResolved) {
    const Farm farm("root_below");
    const OutputRoot root(farm.root);
    EXPECT_EQ(root.below(farm.scenes / "out" / "a"), fs::path("scenes/out/a"));
    EXPECT_THROW(root.below(farm.outside / "out"), OutputError);
    EXPECT_THROW(root.below(farm.root / ".." / "outside"), OutputError);
    fs::create_directory_symlink(farm.outside, farm.scenes / "escape");
    try {
        root.below(farm.scenes / "escape" / "out");
        FAIL() << "a link out of the root was taken";
    } catch (const OutputError& e) {
        EXPECT_NE(std::string(e.what()).find("it leads to " + (fs::canonical(farm.outside) / "out").string()),
                  std::string::npos)
            << e.what();
    }
    // A link that stays inside the root is where it leads.
    fs::create_directory_symlink(farm.scenes, farm.root / "alias");
    EXPECT_EQ(root.below(farm.root / "alias" / "out"), fs::path("scenes/out"));
}

TEST(OutputRoot, DirectoriesAreOpenedWithoutFollowingLinks) {
    const Farm farm("root_open");
    OutputRoot root(farm.root);
    std::vector<fs::path> created;
    const fs::path opened = root.openDirectory("scenes/new/deeper", created);
    EXPECT_EQ(created, (std::vector<fs::path>{fs::canonical(farm.root) / "scenes/new",
                                              fs::canonical(farm.root) / "scenes/new/deeper"}));
    writeText(opened / "probe.txt", "x");
    EXPECT_TRUE(fs::exists(farm.scenes / "new" / "deeper" / "probe.txt"));

    // The check passed while scenes/late was a directory; then it became a link out of the root.
    fs::create_directory(farm.scenes / "late");
    const fs::path relative = root.below(farm.scenes / "late" / "out");
    fs::remove(farm.scenes / "late");
    fs::create_directory_symlink(farm.outside, farm.scenes / "late");
    created.clear();
    try {
        root.openDirectory(relative, created);
        FAIL() << "the swapped link was followed";
    } catch (const OutputError& e) {
        EXPECT_NE(std::string(e.what()).find("late: is a symbolic link"), std::string::npos) << e.what();
    }
    EXPECT_TRUE(created.empty());
    EXPECT_TRUE(treeOf(farm.outside).empty());
}

TEST(OutputRoot, ScenesThatWriteOutsideAreRefusedInOneLineWithNothingWritten) {
    const Farm farm("root_refused");
    fs::create_directory_symlink(farm.outside, farm.scenes / "escape");
    const std::vector<std::string> before = treeOf(farm.dir);
    for (const std::string& directory : {(farm.outside / "out").string(), std::string("escape/out")}) {
        const BakeSummary summary = farm.bake(directory);
        EXPECT_FALSE(summary.ok) << directory;
        EXPECT_NE(summary.error.find("outputs.directory: "), std::string::npos) << summary.error;
        EXPECT_NE(summary.error.find(directory.front() == '/' ? "absolute" : "outside the output root"),
                  std::string::npos)
            << summary.error;
        EXPECT_EQ(summary.error.find('\n'), std::string::npos) << summary.error;
        fs::remove(farm.scenes / "scene.json");
        EXPECT_EQ(treeOf(farm.dir), before) << directory;
    }
}

TEST(OutputRoot, ABakeBelowTheRootWritesThroughTheDirectoryItOpened) {
    const Farm farm("root_bake");
    const BakeSummary summary = farm.bake("out");
    ASSERT_TRUE(summary.ok) << summary.error;
    EXPECT_TRUE(fs::exists(farm.scenes / "out" / "manifest.json"));
    EXPECT_TRUE(fs::exists(farm.scenes / "out" / "specular.ktx2"));
    EXPECT_EQ(summary.manifest, farm.scenes / "out" / "manifest.json"); // reported as the scene names it
    for (const fs::path& product : summary.products)
        EXPECT_EQ(product.string().find("/proc/"), std::string::npos) << product;

    // Once the bake has opened its output directory, the directory is swapped for a link out of the root:
    // the bake goes on writing into the directory it opened, and nothing lands outside.
    struct Swapper : ProgressSink {
        const Farm& farm;
        bool swapped = false;
        explicit Swapper(const Farm& f) : farm(f) {}
        void stageStart(const StageResult&, int, int) override {
            if (swapped) return;
            fs::rename(farm.scenes / "again", farm.scenes / "moved");
            fs::create_directory_symlink(farm.outside, farm.scenes / "again");
            swapped = true;
        }
    } swapper(farm);
    const BakeSummary again = farm.bake("again", swapper);
    ASSERT_TRUE(swapper.swapped);
    EXPECT_TRUE(again.ok) << again.error;
    EXPECT_TRUE(treeOf(farm.outside).empty());
    EXPECT_TRUE(fs::exists(farm.scenes / "moved" / "manifest.json"));
}

TEST(OutputRoot, BatchSummaryAndItemsStayBelowTheRoot) {
    const Farm farm("root_batch");
    writeText(farm.scenes / "batch.json", json{{"items",
                                                {{{"hdri", "sky.exr"},
                                                  {"output", (farm.outside / "item").string()},
                                                  {"preset", "draft"},
                                                  {"faceSize", 16}}}}}
                                              .dump());
    const BatchManifest manifest = loadBatchManifest(farm.scenes / "batch.json");
    BatchRunOptions options;
    options.bake.backend = Backend::Cpu;
    options.bake.outputRoot = farm.root;
    BatchObserver quiet;
    const BatchBakeFunction bake = [](const Scene& scene, const BakeOptions& o, ProgressSink& p,
                                      const UpToDate&) { return bakeScene(scene, o, p); };
    // The summary outside the root: refused before any item.
    options.summaryFile = farm.outside / "summary.json";
    EXPECT_THROW(runBatch(manifest, Shard{}, options, bake, quiet), OutputError);
    EXPECT_TRUE(treeOf(farm.outside).empty());
    // Below the root: the item that names an absolute output fails alone, in one line.
    options.summaryFile = farm.scenes / "summary.json";
    const BatchSummary summary = runBatch(manifest, Shard{}, options, bake, quiet);
    ASSERT_EQ(summary.items.size(), 1u);
    EXPECT_EQ(summary.items[0].status, BatchItemStatus::Failed);
    EXPECT_NE(summary.items[0].error.find("absolute"), std::string::npos) << summary.items[0].error;
    EXPECT_TRUE(treeOf(farm.outside).empty());
    EXPECT_TRUE(fs::exists(farm.scenes / "summary.json"));
}

TEST(OutputRoot, TheCommandLineAndTheEnvironmentSetTheRoot) {
    const Farm farm("root_cli");
    writeText(farm.scenes / "scene.json",
              json{{"environment", {{"file", "sky.exr"}}},
                   {"outputs", {{"directory", (farm.outside / "out").string()}, {"faceSize", 16}}}}
                  .dump());
    const std::string bake = "bake " + (farm.scenes / "scene.json").string() + " --quiet --backend cpu";
    CliRun r = runCli(bake + " --output-root " + farm.root.string());
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_EQ(occurrences(r.err, "\n"), 1u) << r.err;
    EXPECT_NE(r.err.find("outputs.directory: "), std::string::npos) << r.err;
    ::setenv("IBLBAKE_OUTPUT_ROOT", farm.root.c_str(), 1);
    r = runCli(bake);
    ::unsetenv("IBLBAKE_OUTPUT_ROOT");
    EXPECT_EQ(r.exitCode, 1) << r.out;
    EXPECT_NE(r.err.find("is written as an absolute path"), std::string::npos) << r.err;
    EXPECT_TRUE(treeOf(farm.outside).empty());
    // Without a root, today's rules: an absolute output directory is the scene's to name.
    r = runCli(bake);
    EXPECT_EQ(r.exitCode, 0) << r.err;
    EXPECT_TRUE(fs::exists(farm.outside / "out" / "manifest.json"));
}
