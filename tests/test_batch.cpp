// `iblbake batch` end to end on tiny items (16-texel faces, draft): shards of one manifest, run apart,
// together produce exactly the files of one unsharded run, byte for byte, each item by one shard; Slurm and
// Kubernetes job-array variables choose the shard; a batch killed with SIGKILL and restarted finishes the
// rest without touching finished items; a failing item fails the batch (one line in the summary) while the
// others complete; manifest errors name the key path.
#include "cli_runner.h"
#include "scene_test_support.h"

#include <iblbake/batch/batch.h>
#include <iblbake/core/error.h>
#include <iblbake/runtime/runtime_manifest.h>

#include <gtest/gtest.h>

#include <OpenImageIO/imageio.h>
#include <nlohmann/json.hpp>

#include <csignal>
#include <cstdlib>
#include <fcntl.h>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <sys/stat.h>

namespace fs = std::filesystem;
using nlohmann::json;
using namespace ibl::test;

namespace {

json smallOutputs(const std::string& directory) {
    return {{"directory", directory}, {"quality", "draft"}, {"faceSize", 16}, {"dfgSize", 16}};
}

// A batch directory: `count` items alternating between scene files (scene<i>.json, every third with an
// irradiance cube) and HDRI items (16-texel faces, draft), each with its own input image, outputs under out/.
struct BatchDir {
    fs::path dir;
    json manifest = json::array();

    BatchDir(const std::string& name, int count) : dir(freshTempDir(name)) {
        for (int i = 0; i < count; ++i) {
            const std::string image = "env" + std::to_string(i) + ".hdr";
            writeLatLong(dir / image, 0.25f * float(i + 1));
            if (i % 2 == 0) {
                json scene = {{"environment", {{"file", image}}},
                              {"outputs", smallOutputs("out/scene" + std::to_string(i))}};
                if (i % 3 == 0)
                    scene["outputs"]["irradianceCube"] = true, scene["outputs"]["irradianceFaceSize"] = 4;
                writeText(dir / ("scene" + std::to_string(i) + ".json"), scene.dump(2));
                manifest.push_back({{"scene", "scene" + std::to_string(i) + ".json"}});
            } else {
                manifest.push_back({{"hdri", image},
                                    {"id", "hdri" + std::to_string(i)},
                                    {"output", "out/hdri" + std::to_string(i)},
                                    {"preset", "draft"},
                                    {"faceSize", 16}});
            }
        }
    }
    ~BatchDir() { fs::remove_all(dir); }
    fs::path write() const {
        writeText(dir / "batch.json", json{{"items", manifest}}.dump(2));
        return dir / "batch.json";
    }
    json summary(const std::string& file = "batch-summary.json") const {
        return json::parse(readBytes(dir / file));
    }
};

// Every product file under `root` (the cache left out) by its path relative to root.
std::map<std::string, std::string> products(const fs::path& root) {
    std::map<std::string, std::string> files;
    if (!fs::exists(root)) return files;
    for (auto it = fs::recursive_directory_iterator(root); it != fs::recursive_directory_iterator(); ++it) {
        if (it->path().filename() == ".iblbake-cache") {
            it.disable_recursion_pending();
            continue;
        }
        if (it->is_regular_file()) files[fs::relative(it->path(), root).string()] = readBytes(it->path());
    }
    return files;
}

std::map<std::string, std::string> statusById(const json& summary) {
    std::map<std::string, std::string> out;
    for (const json& item : summary["items"])
        out[item["id"]] = item["status"];
    return out;
}

std::vector<json> events(const std::string& out) {
    std::vector<json> all;
    std::istringstream lines(out);
    for (std::string line; std::getline(lines, line);)
        all.push_back(json::parse(line));
    return all;
}

// getenv over a fixed map, for shardFromEnvironment.
std::function<const char*(const char*)> envOf(const std::map<std::string, std::string>& vars) {
    return [vars](const char* name) -> const char* {
        auto it = vars.find(name);
        return it == vars.end() ? nullptr : it->second.c_str();
    };
}

} // namespace

TEST(Batch, ManifestErrorsNameTheKeyPath) {
    const auto error = [](const std::string& text) {
        try {
            ibl::parseBatchManifest(text, "b.json", "/base");
        } catch (const ibl::Error& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    EXPECT_EQ(error(R"({"items": [{"scene": "a.json"}, {"hdri": "x.hdr", "preset": "fast"}]})"),
              "b.json: items[1].preset: 'fast' is not one of draft, production, reference");
    EXPECT_EQ(error(R"([{"scene": "a.json", "outptu": "x"}])"),
              "b.json: items[0].outptu: unknown key (a scene item has \"scene\" and \"id\")");
    EXPECT_EQ(error(R"([{"id": "a"}])"), "b.json: items[0]: needs exactly one of \"scene\" and \"hdri\"");
    EXPECT_EQ(error(R"([{"hdri": "x.hdr", "faceSize": 12}])"),
              "b.json: items[0].faceSize: must be a power of two up to 4096");
    EXPECT_EQ(error(R"([{"hdri": "x.hdr"}, {"scene": "x.hdr"}])"),
              "b.json: items[1].id: 'x.hdr' is used by an earlier item");
    EXPECT_EQ(error(R"([{"hdri": "a/x.hdr"}, {"hdri": "b/x.hdr"}])"),
              "b.json: items[1].output: /base/x is also the output of items[0]");
    EXPECT_EQ(error(R"({"itemz": []})"), "b.json: itemz: unknown key");
    EXPECT_EQ(error(R"({"items": 3})"), "b.json: items: must be an array of items");
    // Text from the file with control bytes (an escaped line break) is quoted: the error stays one line.
    EXPECT_EQ(error(R"({"it\nems": []})"), "b.json: 'it\\x0Aems': unknown key");
    EXPECT_EQ(error(R"([{"scene": "a.json", "i\td": "x"}])"),
              "b.json: items[0].'i\\x09d': unknown key (a scene item has \"scene\" and \"id\")");
    EXPECT_EQ(error(R"([{"hdri": "x.hdr", "preset": "dr\naft"}])"),
              "b.json: items[0].preset: 'dr\\x0Aaft' is not one of draft, production, reference");
    EXPECT_EQ(error(R"([{"hdri": "x.hdr", "id": "a\rb"}, {"scene": "s.json", "id": "a\rb"}])"),
              "b.json: items[0].id: 'a\\x0Db' must be 1 to 128 of A-Z a-z 0-9 _ - . (not . or ..)");
    EXPECT_EQ(error(R"([{"hdri": "x.hdr", "id": "a"}, {"scene": "s.json", "id": "a"}])"),
              "b.json: items[1].id: 'a' is used by an earlier item");
    EXPECT_EQ(error(R"([{"hdri": "x.hdr", "output": "o\n"}])"),
              "b.json: items[0].output: 'o\\x0A' holds control bytes, which no file name may");
    EXPECT_EQ(error(R"([{"hdri": "x.hdr", "output": "o"}, {"hdri": "y.hdr", "output": "o"}])"),
              "b.json: items[1].output: /base/o is also the output of items[0]");

    const ibl::BatchManifest m = ibl::parseBatchManifest(
        R"([{"hdri": "h/x.hdr"}, {"scene": "s.json", "id": "s"}])", "b.json", "/base");
    ASSERT_EQ(m.items.size(), 2u);
    EXPECT_EQ(m.items[0].id, "h/x.hdr");
    EXPECT_EQ(m.items[0].output, fs::path("/base/x"));
    EXPECT_EQ(m.items[0].preset, "production");
    const ibl::Scene scene = ibl::batchItemScene(m, m.items[0]);
    EXPECT_EQ(scene.environment.files.at(0), fs::path("/base/h/x.hdr"));
    EXPECT_EQ(scene.outputs.directory, fs::path("/base/x"));
    EXPECT_EQ(m.items[1].id, "s");
    EXPECT_TRUE(m.items[1].isScene());
}

TEST(Batch, ShardsComeFromTheFlagOrTheSchedulersVariables) {
    const ibl::Shard flag = ibl::parseShard("2/3");
    EXPECT_EQ(flag.index, 1);
    EXPECT_EQ(flag.count, 3);
    EXPECT_THROW(ibl::parseShard("0/3"), ibl::Error);
    EXPECT_THROW(ibl::parseShard("4/3"), ibl::Error);
    EXPECT_THROW(ibl::parseShard("2"), ibl::Error);

    EXPECT_FALSE(ibl::shardFromEnvironment(envOf({}), std::nullopt));
    // Slurm arrays start where --array says: the index is ID - MIN.
    auto slurm = ibl::shardFromEnvironment(
        envOf({{"SLURM_ARRAY_TASK_ID", "5"}, {"SLURM_ARRAY_TASK_MIN", "4"}, {"SLURM_ARRAY_TASK_COUNT", "3"}}),
        std::nullopt);
    ASSERT_TRUE(slurm);
    EXPECT_EQ(slurm->index, 1);
    EXPECT_EQ(slurm->count, 3);
    EXPECT_EQ(slurm->source, "SLURM_ARRAY_TASK_ID");
    slurm = ibl::shardFromEnvironment(
        envOf({{"SLURM_ARRAY_TASK_ID", "3"}, {"SLURM_ARRAY_TASK_MIN", "1"}, {"SLURM_ARRAY_TASK_MAX", "4"}}),
        std::nullopt);
    EXPECT_EQ(slurm->index, 2);
    EXPECT_EQ(slurm->count, 4);
    EXPECT_THROW(ibl::shardFromEnvironment(envOf({{"SLURM_ARRAY_TASK_ID", "3"}}), std::nullopt), ibl::Error);
    EXPECT_THROW(ibl::shardFromEnvironment(
                     envOf({{"SLURM_ARRAY_TASK_ID", "x"}, {"SLURM_ARRAY_TASK_COUNT", "2"}}), std::nullopt),
                 ibl::Error);
    EXPECT_THROW(ibl::shardFromEnvironment(
                     envOf({{"SLURM_ARRAY_TASK_ID", "2"}, {"SLURM_ARRAY_TASK_COUNT", "2"}}), std::nullopt),
                 ibl::Error);

    auto k8s = ibl::shardFromEnvironment(envOf({{"JOB_COMPLETION_INDEX", "2"}}), 3);
    EXPECT_EQ(k8s->index, 2);
    EXPECT_EQ(k8s->count, 3);
    k8s = ibl::shardFromEnvironment(envOf({{"JOB_COMPLETION_INDEX", "0"}, {"IBLBAKE_SHARD_COUNT", "5"}}),
                                    std::nullopt);
    EXPECT_EQ(k8s->count, 5);
    EXPECT_THROW(ibl::shardFromEnvironment(envOf({{"JOB_COMPLETION_INDEX", "0"}}), std::nullopt), ibl::Error);
    EXPECT_THROW(ibl::shardFromEnvironment(envOf({{"JOB_COMPLETION_INDEX", "3"}}), 3), ibl::Error);
}

TEST(Batch, ShardsRunApartGiveTheBytesOfOneRunEachItemOnce) {
    BatchDir whole("batch_whole", 5);
    CliRun all = runCli("batch " + whole.write().string() + " --jobs 2 --quiet");
    ASSERT_EQ(all.exitCode, 0) << all.err;
    const std::map<std::string, std::string> expected = products(whole.dir / "out");
    ASSERT_GE(expected.size(), 5u * 4u);
    EXPECT_TRUE(expected.count("scene0/irradiance.ktx2"));
    for (const auto& [id, status] : statusById(whole.summary()))
        EXPECT_EQ(status, "ok") << id;

    std::map<std::string, std::string> together;
    std::map<std::string, int> bakedBy; // item id -> how many shards baked it
    for (int k = 1; k <= 3; ++k) {
        BatchDir shard("batch_shard" + std::to_string(k), 5); // the same inputs, a separate root
        CliRun r = runCli("batch " + shard.write().string() + " --shard " + std::to_string(k) + "/3 --json");
        ASSERT_EQ(r.exitCode, 0) << r.err;
        const json summary = shard.summary("batch-summary-" + std::to_string(k) + "-of-3.json");
        EXPECT_EQ(summary["shard"]["index"], k);
        EXPECT_TRUE(summary["complete"].get<bool>());
        for (const json& item : summary["items"]) {
            const bool mine = item["index"].get<int>() % 3 == k - 1; // index mod N = K - 1
            EXPECT_EQ(item["status"], mine ? "ok" : "not-in-shard") << item["id"];
            bakedBy[item["id"]] += item["status"] == "ok";
        }
        for (auto& [file, bytes] : products(shard.dir / "out")) {
            EXPECT_FALSE(together.count(file)) << file << " produced by two shards";
            together[file] = bytes;
        }
    }
    for (const auto& [id, n] : bakedBy)
        EXPECT_EQ(n, 1) << id;
    ASSERT_EQ(together.size(), expected.size());
    for (const auto& [file, bytes] : expected) {
        ASSERT_TRUE(together.count(file)) << file;
        EXPECT_TRUE(together[file] == bytes) << file << " differs";
    }
}

TEST(Batch, SlurmAndKubernetesVariablesChooseTheShard) {
    BatchDir d("batch_env", 3);
    const std::string manifest = d.write().string();
    // Slurm array --array=4-6: task 6 is the third shard of three.
    ::setenv("SLURM_ARRAY_TASK_ID", "6", 1);
    ::setenv("SLURM_ARRAY_TASK_MIN", "4", 1);
    ::setenv("SLURM_ARRAY_TASK_COUNT", "3", 1);
    CliRun slurm = runCli("batch " + manifest + " --quiet");
    ::unsetenv("SLURM_ARRAY_TASK_ID");
    ::unsetenv("SLURM_ARRAY_TASK_MIN");
    ::unsetenv("SLURM_ARRAY_TASK_COUNT");
    ASSERT_EQ(slurm.exitCode, 0) << slurm.err;
    json s = d.summary("batch-summary-3-of-3.json");
    EXPECT_EQ(s["shard"]["source"], "SLURM_ARRAY_TASK_ID");
    EXPECT_EQ(statusById(s),
              (std::map<std::string, std::string>{
                  {"scene0.json", "not-in-shard"}, {"hdri1", "not-in-shard"}, {"scene2.json", "ok"}}));

    // Kubernetes indexed job: JOB_COMPLETION_INDEX 1 of --shard-count 3, then of IBLBAKE_SHARD_COUNT 3.
    ::setenv("JOB_COMPLETION_INDEX", "1", 1);
    CliRun k8s = runCli("batch " + manifest + " --quiet --shard-count 3");
    ::setenv("IBLBAKE_SHARD_COUNT", "3", 1);
    CliRun k8sEnv = runCli("batch " + manifest + " --json");
    ::unsetenv("JOB_COMPLETION_INDEX");
    ::unsetenv("IBLBAKE_SHARD_COUNT");
    ASSERT_EQ(k8s.exitCode, 0) << k8s.err;
    ASSERT_EQ(k8sEnv.exitCode, 0) << k8sEnv.err;
    s = d.summary("batch-summary-2-of-3.json");
    EXPECT_EQ(s["shard"]["source"], "JOB_COMPLETION_INDEX");
    EXPECT_EQ(statusById(s), (std::map<std::string, std::string>{{"scene0.json", "not-in-shard"},
                                                                 {"hdri1", "up-to-date"},
                                                                 {"scene2.json", "not-in-shard"}}));
    EXPECT_TRUE(fs::exists(d.dir / "out/hdri1/manifest.json"));
    EXPECT_FALSE(fs::exists(d.dir / "out/scene0"));

    // --shard wins over the variables.
    ::setenv("JOB_COMPLETION_INDEX", "1", 1);
    CliRun flag =
        runCli("batch " + manifest + " --quiet --shard 1/2 --summary " + (d.dir / "flag.json").string());
    ::unsetenv("JOB_COMPLETION_INDEX");
    ASSERT_EQ(flag.exitCode, 0) << flag.err;
    EXPECT_EQ(d.summary("flag.json")["shard"]["source"], "--shard");
}

TEST(Batch, AFailingItemFailsTheBatchAndTheOthersComplete) {
    BatchDir d("batch_fail", 3);
    d.manifest.insert(d.manifest.begin() + 1,
                      json{{"hdri", "missing.hdr"}, {"faceSize", 16}, {"preset", "draft"}});
    CliRun r = runCli("batch " + d.write().string() + " --jobs 2");
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_NE(r.err.find("iblbake: error: 1 of 4 items failed"), std::string::npos) << r.err;
    const json s = d.summary();
    EXPECT_TRUE(s["complete"].get<bool>());
    EXPECT_FALSE(s["ok"].get<bool>());
    for (const json& item : s["items"]) {
        if (item["id"] == "missing.hdr") {
            EXPECT_EQ(item["status"], "failed");
            const std::string error = item["error"];
            EXPECT_EQ(error.find('\n'), std::string::npos);
            EXPECT_NE(error.find("items[1]: environment.file"), std::string::npos) << error;
            EXPECT_NE(error.find("missing.hdr"), std::string::npos) << error;
        } else {
            EXPECT_EQ(item["status"], "ok") << item["id"];
            EXPECT_NO_THROW(ibl::loadProbeSetFromManifest(fs::path(item["output"].get<std::string>())));
        }
    }
    EXPECT_FALSE(fs::exists(d.dir / "missing"));
}

namespace {

// `iblbake batch MANIFEST --json` as a child process whose stdout is read line by line.
struct Child {
    pid_t pid = -1;
    FILE* out = nullptr;
};

Child spawnBatch(const std::string& manifest) {
    int fds[2];
    if (::pipe(fds) != 0) return {};
    const pid_t pid = ::fork();
    if (pid == 0) {
        ::dup2(fds[1], STDOUT_FILENO);
        const int devNull = ::open("/dev/null", O_WRONLY);
        ::dup2(devNull, STDERR_FILENO);
        ::close(fds[0]);
        ::close(fds[1]);
        ::execl(IBLBAKE_CLI, IBLBAKE_CLI, "batch", manifest.c_str(), "--json", "--jobs", "1", (char*)nullptr);
        ::_exit(127);
    }
    ::close(fds[1]);
    return {pid, ::fdopen(fds[0], "r")};
}

struct FileStamp {
    ino_t inode;
    struct timespec mtime;
    bool operator==(const FileStamp& o) const {
        return inode == o.inode && mtime.tv_sec == o.mtime.tv_sec && mtime.tv_nsec == o.mtime.tv_nsec;
    }
};

std::map<std::string, FileStamp> stamps(const fs::path& dir) {
    std::map<std::string, FileStamp> out;
    for (const auto& e : fs::directory_iterator(dir))
        if (e.is_regular_file()) {
            struct stat st {};
            ::stat(e.path().c_str(), &st);
            out[e.path().filename().string()] = {st.st_ino, st.st_mtim};
        }
    return out;
}

} // namespace

TEST(Batch, KilledAndRestartedFinishesTheRestWithoutRedoingFinishedItems) {
    BatchDir d("batch_kill", 6);
    const std::string manifest = d.write().string();
    Child child = spawnBatch(manifest);
    ASSERT_GT(child.pid, 0);
    std::set<std::string> finished; // items whose item-end (status ok) the first run printed
    std::string killedDuring;
    char* line = nullptr;
    std::size_t capacity = 0;
    while (::getline(&line, &capacity, child.out) > 0) {
        const json event = json::parse(line);
        if (event["event"] == "item-end" && event["status"] == "ok") finished.insert(event["item"]);
        // A later item has begun a stage: kill the batch in the middle of it.
        if (event["event"] == "stage-start" && !finished.empty() && !finished.count(event["item"])) {
            killedDuring = event["item"];
            ::kill(child.pid, SIGKILL);
            break;
        }
    }
    std::free(line);
    std::fclose(child.out);
    int status = 0;
    ::waitpid(child.pid, &status, 0);
    ASSERT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGKILL) << "the batch ended before it was killed";
    ASSERT_FALSE(finished.empty());
    // The summary written so far shows the finished items (and the rest pending, but for the one the kill
    // may have just missed).
    for (const auto& [id, s] : statusById(d.summary())) {
        if (finished.count(id)) {
            EXPECT_EQ(s, "ok") << id;
        } else if (id != killedDuring) {
            EXPECT_EQ(s, "pending") << id;
        }
    }

    std::map<std::string, fs::path> outputOf;
    const json killedSummary = d.summary();
    for (const json& item : killedSummary["items"])
        if (item.contains("output")) outputOf[item["id"]] = item["output"].get<std::string>();
    std::map<std::string, std::map<std::string, FileStamp>> before;
    for (const std::string& id : finished)
        before[id] = stamps(outputOf.at(id));

    CliRun again = runCli("batch " + manifest + " --json --jobs 1");
    ASSERT_EQ(again.exitCode, 0) << again.err;
    std::set<std::string> stagesRan;
    std::map<std::string, std::string> ended;
    for (const json& event : events(again.out)) {
        if (event["event"] == "stage-start") stagesRan.insert(event["item"]);
        if (event["event"] == "item-end") ended[event["item"]] = event["status"];
    }
    const json summary = d.summary();
    EXPECT_TRUE(summary["complete"].get<bool>());
    ASSERT_EQ(summary["items"].size(), 6u);
    for (const json& item : summary["items"]) {
        const std::string id = item["id"];
        if (finished.count(id)) {
            EXPECT_EQ(item["status"], "up-to-date") << id;
            EXPECT_EQ(ended[id], "up-to-date") << id;
            EXPECT_FALSE(stagesRan.count(id)) << id << " was recomputed";
            EXPECT_EQ(item["stages"]["ran"], 0);
            EXPECT_TRUE(stamps(item["output"].get<std::string>()) == before[id])
                << id << " files were rewritten";
        } else {
            EXPECT_TRUE(item["status"] == "ok" || item["status"] == "up-to-date") << id << item.dump();
        }
        const fs::path out = item["output"].get<std::string>();
        const ibl::ManifestProbeSet set =
            ibl::loadProbeSetFromManifest(out); // every product present and valid
        EXPECT_TRUE(set.options.specular) << id;
        for (const json& product : item["products"])
            EXPECT_TRUE(fs::exists(product.get<std::string>())) << product;
    }
    EXPECT_TRUE(ended.count(killedDuring)); // the interrupted item was finished by the restart
}

// The front end (cli/front_end.cpp) answers a batch whose shard is all up to date without the engine, with
// the summary the engine would write; a batch with anything to bake needs the engine.
TEST(Batch, UnchangedBatchIsAnsweredWithoutTheEngineAndAsTheEngineWould) {
    BatchDir d("batch_front_end", 3);
    const std::string manifest = d.write().string();
    ASSERT_EQ(runCli("batch " + manifest + " --quiet").exitCode, 0);
    const auto before = products(d.dir / "out");
    const std::string withoutEngine =
        "env IBLBAKE_ENGINE=" + (d.dir / "no-engine").string() + " " + IBLBAKE_CLI;

    const auto comparable = [](json summary) {
        summary.erase("seconds");
        for (json& item : summary["items"])
            item.erase("seconds");
        return summary;
    };
    CliRun front = runProgram(withoutEngine, "batch " + manifest + " --json");
    ASSERT_EQ(front.exitCode, 0) << front.err;
    const json frontSummary = d.summary();
    EXPECT_TRUE(frontSummary["complete"].get<bool>());
    EXPECT_EQ(frontSummary["counts"]["up-to-date"], 3);
    EXPECT_EQ(events(front.out).back()["event"], "done");
    EXPECT_EQ(products(d.dir / "out"), before);

    CliRun engine = runProgram(enginePath(), "batch " + manifest + " --json");
    ASSERT_EQ(engine.exitCode, 0) << engine.err;
    EXPECT_EQ(comparable(d.summary()), comparable(frontSummary));

    CliRun shard = runProgram(withoutEngine, "batch " + manifest + " --quiet --shard 2/2");
    EXPECT_EQ(shard.exitCode, 0) << shard.err;
    EXPECT_EQ(d.summary("batch-summary-2-of-2.json")["counts"]["up-to-date"], 1);

    writeLatLong(d.dir / "env1.hdr", 7.0f); // item hdri1 must be baked again
    for (const std::string& args : {"batch " + manifest + " --quiet", "batch " + manifest + " --force"}) {
        CliRun r = runProgram(withoutEngine, args);
        EXPECT_EQ(r.exitCode, 1) << args;
        EXPECT_NE(r.err.find("cannot run the engine"), std::string::npos) << r.err;
    }
    ASSERT_EQ(runCli("batch " + manifest + " --quiet").exitCode, 0);
    EXPECT_EQ(statusById(d.summary()),
              (std::map<std::string, std::string>{
                  {"scene0.json", "up-to-date"}, {"hdri1", "ok"}, {"scene2.json", "up-to-date"}}));
}
