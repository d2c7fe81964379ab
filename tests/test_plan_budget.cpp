// A memory and work budget from the plan (issue 44, docs/scenes.md "Budget"): the estimate is within 2x of
// the measured peak on the example scene and an HDRI item, and a scene of many large probes is refused in one
// line, fast, small and writing nothing; in a batch, the item over budget fails alone.
#include "cli_runner.h"
#include "scene_test_support.h"

#include <iblbake/batch/batch.h>
#include <iblbake/core/error.h>
#include <iblbake/scene/plan_budget.h>
#include <iblbake/scene/scene.h>
#include <iblbake/scene/scene_plan.h>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <sys/resource.h>
#include <sys/wait.h>

namespace fs = std::filesystem;
using nlohmann::json;
using namespace ibl;
using namespace ibl::test;

namespace {

struct ChildRun {
    int exitCode = -1;
    double peakMiB = 0.0; // the child's peak resident set (wait4's ru_maxrss)
    double seconds = 0.0;
};

// `command` through /bin/sh, which execs it (the front end execs the engine in the same process), its
// output to `log`.
ChildRun runMeasured(const std::string& command, const fs::path& log) {
    const auto start = std::chrono::steady_clock::now();
    const pid_t pid = ::fork();
    if (pid == 0) {
        const std::string line = "exec " + command + " >" + log.string() + " 2>&1";
        ::execl("/bin/sh", "sh", "-c", line.c_str(), static_cast<char*>(nullptr));
        ::_exit(127);
    }
    int status = 0;
    struct rusage usage {};
    ::wait4(pid, &status, 0, &usage);
    ChildRun run;
    run.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    run.peakMiB = double(usage.ru_maxrss) / 1024.0;
    run.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return run;
}

double estimateMiB(const Scene& scene) {
    return double(estimatePlan(scene, planScene(scene)).peakBytes) / (1024.0 * 1024.0);
}

// The example scene, its HDRI named by its absolute path, baking into `dir`.
fs::path exampleSceneIn(const fs::path& dir) {
    json scene = json::parse(readBytes(fs::path(IBLBAKE_SOURCE_DIR) / "data/scenes/park.json"));
    scene["environment"]["file"] = kSampleHdri;
    for (json& probe : scene["probes"])
        probe["capture"] = kSampleHdri;
    writeText(dir / "park.json", scene.dump());
    return dir / "park.json";
}

// `count` probes of `probeFaceSize`-px faces, all capturing `capture`.
fs::path manyProbesScene(const fs::path& dir, int count, int probeFaceSize, bool preview) {
    json probes = json::array();
    for (int i = 0; i < count; ++i)
        probes.push_back({{"name", "p" + std::to_string(i)},
                          {"capture", "sky.exr"},
                          {"position", {i, 1, 0}},
                          {"proxy", {{"shape", "sphere"}, {"radius", 2}}}});
    json outputs = {{"directory", "out"}, {"probeFaceSize", probeFaceSize}};
    if (preview) outputs["preview"] = true;
    writeText(dir / "many.json",
              json{{"environment", {{"file", "sky.exr"}}}, {"probes", probes}, {"outputs", outputs}}.dump());
    return dir / "many.json";
}

} // namespace

TEST(PlanBudget, EstimatesAreWithinTwiceTheMeasuredPeaks) {
    const fs::path dir = freshTempDir("budget_measured");
    const fs::path park = exampleSceneIn(dir);
    writeText(dir / "batch.json",
              json{{"items", {{{"hdri", kSampleHdri}, {"output", "item"}, {"id", "item"}}}}}.dump());
    const BatchManifest manifest = loadBatchManifest(dir / "batch.json");
    const struct {
        std::string name, command;
        double estimate;
    } cases[] = {
        {"park.json", std::string(IBLBAKE_CLI) + " bake " + park.string() + " --quiet",
         estimateMiB(loadSceneFile(park))},
        {"HDRI item, 256-px faces",
         std::string(IBLBAKE_CLI) + " batch " + (dir / "batch.json").string() + " --quiet",
         estimateMiB(batchItemScene(manifest, manifest.items.at(0)))},
    };
    for (const auto& c : cases) {
        const ChildRun run = runMeasured(c.command, dir / "log.txt");
        ASSERT_EQ(run.exitCode, 0) << c.name << ": " << readBytes(dir / "log.txt");
        const double ratio = c.estimate / run.peakMiB;
        std::printf("%s: estimate %.0f MiB, measured peak %.0f MiB (x%.2f), %.2f s\n", c.name.c_str(),
                    c.estimate, run.peakMiB, ratio, run.seconds);
        EXPECT_GE(ratio, 0.5) << c.name;
        EXPECT_LE(ratio, 2.0) << c.name;
    }
    fs::remove_all(dir);
}

TEST(PlanBudget, ManyLargeProbesAreRefusedInOneLineWritingNothing) {
    const fs::path dir = freshTempDir("budget_many_probes");
    writeLatLong(dir / "sky.exr", 0.3f);
    const fs::path scene = manyProbesScene(dir, 2000, 4096, false);
    const struct {
        std::string flags, expected;
    } cases[] = {
        {"--max-memory 4G",
         "many.json: outputs.probeFaceSize: the plan needs an estimated 8.0 GiB (probe:p0: "
         "4,096-px faces), over --max-memory 4.0 GiB"},
        {"--max-work 1e12", "many.json: outputs.probeFaceSize: the plan needs an estimated 1.72e+13 "
                            "texel-samples (2,000 probe-ld stages of 4,096-px faces), over --max-work 1e+12"},
    };
    for (const auto& c : cases) {
        const ChildRun run = runMeasured(std::string(IBLBAKE_CLI) + " bake " + scene.string() + " " + c.flags,
                                         dir / "log.txt");
        const std::string log = readBytes(dir / "log.txt");
        EXPECT_EQ(run.exitCode, 1) << log;
        EXPECT_EQ(log, "iblbake: error: " + scene.string() +
                           c.expected.substr(std::string("many.json").size()) + "\n");
        EXPECT_LT(run.peakMiB, 100.0)
            << c.flags;                // refused before any work (no timer: CI machines are shared)
        std::vector<std::string> left; // nothing written anywhere in the scene's directory
        for (const fs::directory_entry& e : fs::directory_iterator(dir))
            left.push_back(e.path().filename().string());
        std::sort(left.begin(), left.end());
        EXPECT_EQ(left, (std::vector<std::string>{"log.txt", "many.json", "sky.exr"})) << c.flags;
    }
    // The preview loads every probe at once: over this machine's default limit without a flag.
    manyProbesScene(dir, 2000, 4096, true);
    const CliRun byDefault = runCli("bake " + scene.string());
    EXPECT_EQ(byDefault.exitCode, 1);
    EXPECT_NE(byDefault.err.find("many.json: probes: the plan needs an estimated "), std::string::npos)
        << byDefault.err;
    EXPECT_NE(byDefault.err.find("(preview: 2,000 probes of 4,096-px faces), over --max-memory "),
              std::string::npos)
        << byDefault.err;
    EXPECT_NE(byDefault.err.find("(75% of this machine's memory)"), std::string::npos) << byDefault.err;
    EXPECT_EQ(lineCount(byDefault.err), 1) << byDefault.err;
    EXPECT_FALSE(fs::exists(dir / "out"));
    // `iblbake plan` prints the estimates.
    const CliRun plan = runCli("plan " + scene.string());
    EXPECT_EQ(plan.exitCode, 0) << plan.err;
    EXPECT_NE(plan.out.find("budget  probe:p1999         7.9 GiB"), std::string::npos) << plan.out;
    fs::remove_all(dir);
}

TEST(PlanBudget, BatchItemOverBudgetFailsAlone) {
    const fs::path dir = freshTempDir("budget_batch");
    writeLatLong(dir / "sky.exr", 0.3f);
    writeText(dir / "batch.json",
              json{{"items",
                    {{{"hdri", "sky.exr"},
                      {"output", "small"},
                      {"preset", "draft"},
                      {"faceSize", 16},
                      {"id", "small"}},
                     {{"hdri", "sky.exr"}, {"output", "large"}, {"faceSize", 4096}, {"id", "large"}}}}}
                  .dump());
    const CliRun run =
        runCli("batch " + (dir / "batch.json").string() + " --max-memory 1G --backend cpu --quiet");
    EXPECT_EQ(run.exitCode, 1) << run.err;
    const json summary = json::parse(readBytes(dir / "batch-summary.json"));
    EXPECT_EQ(summary.at("items").at(0).at("status"), "ok");
    EXPECT_EQ(summary.at("items").at(1).at("status"), "failed");
    EXPECT_NE(summary.at("items").at(1).at("error").get<std::string>().find(
                  "outputs.faceSize: the plan needs an estimated "),
              std::string::npos)
        << summary.dump();
    EXPECT_TRUE(fs::exists(dir / "small" / "manifest.json"));
    EXPECT_FALSE(fs::exists(dir / "large"));
    // A finished bake is not answered up to date once over a budget given later: refused, by the front end
    // as by the engine.
    writeText(dir / "small.json",
              json{{"environment", {{"file", "sky.exr"}}},
                   {"outputs", {{"directory", "small_scene"}, {"quality", "draft"}, {"faceSize", 16}}}}
                  .dump());
    ASSERT_EQ(runCli("bake " + (dir / "small.json").string() + " --backend cpu --quiet").exitCode, 0);
    for (const std::string& program : {std::string(IBLBAKE_CLI), enginePath()}) {
        const CliRun refused =
            runProgram(program, "bake " + (dir / "small.json").string() + " --max-memory 1M");
        EXPECT_EQ(refused.exitCode, 1) << program;
        EXPECT_NE(refused.err.find("small.json: outputs.dfgSize: the plan needs an estimated "),
                  std::string::npos)
            << refused.err;
        EXPECT_NE(refused.err.find(", over --max-memory 1.0 MiB"), std::string::npos) << refused.err;
    }
    fs::remove_all(dir);
}

TEST(PlanBudget, SizesAndCountsParse) {
    EXPECT_EQ(parseByteSize("4G", "--max-memory"), std::uint64_t(4) << 30);
    EXPECT_EQ(parseByteSize("1.5GiB", "--max-memory"), std::uint64_t(3) << 29);
    EXPECT_EQ(parseByteSize("512M", "--max-memory"), std::uint64_t(512) << 20);
    EXPECT_EQ(parseByteSize("1000", "--max-memory"), 1000u);
    EXPECT_EQ(parseWorkCount("2e12", "--max-work"), std::uint64_t(2000000000000));
    EXPECT_EQ(parseWorkCount("500G", "--max-work"), std::uint64_t(500000000000));
    for (const char* bad : {"", "G", "4X", "-1", "0", "4GB extra", "nan"})
        EXPECT_THROW(parseByteSize(bad, "--max-memory"), Error) << bad;
    EXPECT_THROW(parseWorkCount("1e30", "--max-work"), Error);
    const CliRun run =
        runCli("bake " + std::string(IBLBAKE_SOURCE_DIR) + "/data/scenes/park.json --max-memory 4X");
    EXPECT_NE(run.exitCode, 0);
    EXPECT_NE(run.err.find("--max-memory: '4X' is not a memory size"), std::string::npos) << run.err;
}

TEST(PlanBudget, SourceSizeFromTheHeaderDrivesTheEnvironmentStage) {
    const fs::path dir = freshTempDir("budget_header");
    writeLatLong(dir / "small.exr", 0.3f); // 64 x 32
    writeRgbFloatImage(dir / "wide.exr", 1024, 512, std::vector<float>(1024 * 512 * 3, 0.5f));
    Scene scene;
    scene.name = "s.json";
    scene.outputs.faceSize = 16;
    scene.environment.files = {dir / "small.exr"};
    const PlanBudget small = estimatePlan(scene, planScene(scene));
    scene.environment.files = {dir / "wide.exr"};
    const PlanBudget wide = estimatePlan(scene, planScene(scene));
    const auto environment = [](const PlanBudget& b) {
        for (const StageEstimate& e : b.stages)
            if (e.id == "environment") return e;
        return StageEstimate{};
    };
    // An OpenEXR lat-long is resampled as it is decoded: blocks of 2,048 rows of 1,024 pixels (2 Mi pixels;
    // the 64 x 32 image is one block of its own size), at most 8 held as fp32 RGBA, a block's fp32 RGB strip
    // and the table of 3 x 16^2 texels (20 bytes each), beside two 16-px cubes.
    const std::uint64_t cube = 6u * 16u * 16u * 16u, texelTable = 3u * 16u * 16u * 20u;
    EXPECT_EQ(environment(small).memoryBytes, 64u * 32u * (16u + 12u) + texelTable + 2 * cube);
    EXPECT_EQ(environment(wide).memoryBytes, 1024u * 512u * (16u + 12u) + texelTable + 2 * cube);
    EXPECT_EQ(environment(wide).drivingKey, "environment.file");
    EXPECT_EQ(environment(wide).what, "524,288-pixel source");
    // A Radiance file is held whole: 20 bytes a source pixel (fp32 RGBA and the RGBE bytes).
    scene.environment.files = {kSampleHdri}; // "-Y 512 +X 1024"
    EXPECT_EQ(environment(estimatePlan(scene, planScene(scene))).memoryBytes, 1024u * 512u * 20u + 2 * cube);
    EXPECT_EQ(environment(estimatePlan(scene, planScene(scene))).what, "524,288-pixel source");
    fs::remove_all(dir);
}
