// Stage-cache keys know the code (docs/scenes.md "Cache"): each key holds its stage kind's code identity, so
// a changed kernel or stage reaches that stage and every stage downstream of it, nothing else, and unchanged
// code keeps every key. The identity table itself is checked by running cmake/StageCodeIdentity.cmake on
// copies of the source tree with one file edited.
#include "cli_runner.h"
#include "scene_test_support.h"
#include "stage_keys.h"

#include <iblbake/bake_state/code_identity.h>
#include <iblbake/baker/bake_scene.h>
#include <iblbake/core/error.h>
#include <iblbake/scene/scene.h>
#include <iblbake/scene/scene_plan.h>

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <regex>
#include <set>
#include <sstream>
#include <string>

namespace {

namespace fs = std::filesystem;
using Keys = std::map<std::string, std::string>;

// The example scene, with the irradiance cube on so that every stage kind is planned.
ibl::Plan everyKindPlan() {
    const fs::path scenes = fs::path(IBLBAKE_SOURCE_DIR) / "data" / "scenes";
    std::ifstream in(scenes / "park.json");
    nlohmann::json scene = nlohmann::json::parse(in);
    // Every kind, whatever park.json asks for.
    scene["outputs"]["irradianceCube"] = true;
    scene["outputs"]["gltf"] = true;
    scene["outputs"]["preview"] = true;
    scene["lights"] = {
        {{"name", "window"}, {"texture", "../rooitou_park_1k.hdr"}, {"cardSize", 16}, {"lumens", 800}}};
    return ibl::planScene(ibl::parseScene(scene.dump(), "park.json", scenes));
}

// Stand-in content hashes: the keys only combine them.
Keys fakeInputHashes(const ibl::Plan& plan) {
    Keys hashes;
    for (const ibl::PlanStage& stage : plan.stages)
        for (const ibl::PlanInput& input : stage.inputs)
            hashes[input.file.string()] = "content of " + input.file.string();
    return hashes;
}

// The ids of the stages of `kind` and of every stage that depends on one of them, directly or not.
std::set<std::string> kindAndDownstream(const ibl::Plan& plan, const std::string& kind) {
    std::set<std::string> reached;
    for (const ibl::PlanStage& stage : plan.stages) { // dependencies come earlier in the plan
        bool hit = stage.kind == kind;
        for (const std::string& dependency : stage.dependsOn)
            hit = hit || reached.count(dependency);
        if (hit) reached.insert(stage.id);
    }
    return reached;
}

std::set<std::string> changedIds(const Keys& before, const Keys& after) {
    std::set<std::string> changed;
    for (const auto& [id, key] : before)
        if (after.at(id) != key) changed.insert(id);
    return changed;
}

std::set<std::string> plannedKinds(const ibl::Plan& plan) {
    std::set<std::string> kinds;
    for (const ibl::PlanStage& stage : plan.stages)
        kinds.insert(stage.kind);
    return kinds;
}

TEST(StageKeys, SameCodeGivesSameKeys) {
    const ibl::Plan plan = everyKindPlan();
    const Keys inputs = fakeInputHashes(plan);
    const Keys keys = ibl::planStageKeys(plan, inputs, "cpu");
    EXPECT_EQ(keys.size(), plan.stages.size());
    EXPECT_EQ(ibl::planStageKeys(plan, inputs, "cpu"), keys);
    const ibl::StageCodeIdentity copy = ibl::builtInStageCodeIdentity();
    EXPECT_EQ(ibl::planStageKeys(plan, inputs, "cpu", copy), keys);
}

TEST(StageKeys, ChangedCodeReachesItsStagesAndEverythingDownstreamOnly) {
    const ibl::Plan plan = everyKindPlan();
    const Keys inputs = fakeInputHashes(plan);
    const Keys before = ibl::planStageKeys(plan, inputs, "cpu");
    for (const std::string& kind : plannedKinds(plan)) {
        ibl::StageCodeIdentity code = ibl::builtInStageCodeIdentity();
        code.at(kind) += "-changed";
        const std::set<std::string> changed =
            changedIds(before, ibl::planStageKeys(plan, inputs, "cpu", code));
        EXPECT_EQ(changed, kindAndDownstream(plan, kind)) << kind;
        EXPECT_FALSE(changed.empty()) << kind;
        EXPECT_LT(changed.size(), plan.stages.size()) << kind; // each kind leaves some stage alone here
    }
}

// The preview's reference has a key of its own (issue 46): the calibrated environment and the balls decide
// it, so a new roughness range or new LD settings re-run the chain and the preview, not the reference; a
// changed environment or ball size re-runs it.
TEST(StageKeys, PreviewReferenceKeyFollowsTheEnvironmentAndTheBallsOnly) {
    const fs::path scenes = fs::path(IBLBAKE_SOURCE_DIR) / "data" / "scenes";
    std::ifstream in(scenes / "park.json");
    const nlohmann::json park = nlohmann::json::parse(in);
    const auto keysOf = [&](const nlohmann::json& scene, const std::string& environmentContent) {
        const ibl::Plan plan = ibl::planScene(ibl::parseScene(scene.dump(), "park.json", scenes));
        Keys inputs = fakeInputHashes(plan);
        for (const ibl::PlanStage& stage : plan.stages)
            if (stage.id == "environment") inputs[stage.inputs.at(0).file.string()] = environmentContent;
        return ibl::planStageKeys(plan, inputs, "cpu");
    };
    const Keys before = keysOf(park, "park");
    ASSERT_TRUE(before.count("preview-reference"));
    EXPECT_EQ(keysOf(park, "park"), before);

    nlohmann::json rougher = park;
    rougher["materials"]["roughness"]["max"] = 0.6;
    EXPECT_EQ(changedIds(before, keysOf(rougher, "park")),
              (std::set<std::string>{"specular", "probe:pavilion", "gltf", "preview"}));
    nlohmann::json draft = park;
    draft["outputs"]["quality"] = "draft";
    const std::set<std::string> draftChanged = changedIds(before, keysOf(draft, "park"));
    EXPECT_TRUE(draftChanged.count("specular") && draftChanged.count("preview"));
    EXPECT_FALSE(draftChanged.count("preview-reference"));

    EXPECT_TRUE(changedIds(before, keysOf(park, "another environment")).count("preview-reference"));
    nlohmann::json smallerBalls = park;
    smallerBalls["outputs"]["preview"] = {{"sphereSize", 32}};
    EXPECT_TRUE(changedIds(before, keysOf(smallerBalls, "park")).count("preview-reference"));
}

TEST(StageKeys, KindWithoutCodeIdentityIsAnError) {
    const ibl::Plan plan = everyKindPlan();
    ibl::StageCodeIdentity code = ibl::builtInStageCodeIdentity();
    code.erase("specular-ld");
    try {
        ibl::planStageKeys(plan, fakeInputHashes(plan), "cpu", code);
        FAIL() << "no error";
    } catch (const ibl::Error& e) {
        EXPECT_NE(std::string(e.what()).find("specular-ld"), std::string::npos) << e.what();
    }
}

TEST(StageCodeIdentity, BuiltInNamesEveryPlannedKindWithItsOwnHash) {
    const ibl::StageCodeIdentity& code = ibl::builtInStageCodeIdentity();
    for (const std::string& kind : plannedKinds(everyKindPlan()))
        EXPECT_TRUE(code.count(kind)) << kind;
    std::set<std::string> distinct;
    for (const auto& [kind, hash] : code) {
        EXPECT_TRUE(std::regex_match(hash, std::regex("[0-9a-f]{64}"))) << kind << ": " << hash;
        distinct.insert(hash);
    }
    EXPECT_EQ(distinct.size(), code.size()); // every kind's source list differs
    EXPECT_TRUE(std::regex_match(std::string(ibl::builtInCodeDigest()), std::regex("[0-9a-f]{12}")));
}

// A copy of the sources the identity script reads, in a fresh directory of its own.
class SourceCopy {
  public:
    SourceCopy() : root_(fs::temp_directory_path() / ("iblbake-stage-code-" + std::to_string(getpid()))) {
        fs::remove_all(root_);
        for (const char* folder : {"baker/src", "baker/oiio_module", "baker/include", "baker/runtime/src",
                                   "baker/runtime/include", "kernels", "cmake"}) {
            fs::create_directories(root_ / folder);
            fs::copy(fs::path(IBLBAKE_SOURCE_DIR) / folder, root_ / folder, fs::copy_options::recursive);
        }
    }
    ~SourceCopy() { fs::remove_all(root_); }
    SourceCopy(const SourceCopy&) = delete;
    SourceCopy& operator=(const SourceCopy&) = delete;

    void append(const std::string& file, const std::string& text) {
        std::ofstream(root_ / file, std::ios::app) << text;
    }
    void restore(const std::string& file) {
        fs::copy_file(fs::path(IBLBAKE_SOURCE_DIR) / file, root_ / file,
                      fs::copy_options::overwrite_existing);
    }

    // The table cmake/StageCodeIdentity.cmake generates from this copy.
    ibl::StageCodeIdentity identity() const {
        const fs::path output = root_ / "identity.cpp";
        const std::string command = std::string("\"") + IBLBAKE_CMAKE + "\" -DSOURCE_ROOT=" + root_.string() +
                                    " -DOUTPUT=" + output.string() + " -P " +
                                    (root_ / "cmake" / "StageCodeIdentity.cmake").string();
        EXPECT_EQ(std::system(command.c_str()), 0) << command;
        std::ifstream in(output);
        const std::string text{std::istreambuf_iterator<char>(in), {}};
        ibl::StageCodeIdentity table;
        const std::regex entry("\\{\"([a-z-]+)\", \"([0-9a-f]{64})\"\\}");
        for (auto m = std::sregex_iterator(text.begin(), text.end(), entry); m != std::sregex_iterator(); ++m)
            table[(*m)[1]] = (*m)[2];
        return table;
    }

  private:
    fs::path root_;
};

std::set<std::string> changedKinds(const ibl::StageCodeIdentity& before,
                                   const ibl::StageCodeIdentity& after) {
    std::set<std::string> changed;
    for (const auto& [kind, hash] : before)
        if (after.at(kind) != hash) changed.insert(kind);
    return changed;
}

TEST(StageCodeIdentity, SourceTextReachesTheKindsThatUseIt) {
    SourceCopy sources;
    // Another checkout of the same code, in another directory: the very table of this build.
    const ibl::StageCodeIdentity unchanged = sources.identity();
    EXPECT_EQ(unchanged, ibl::builtInStageCodeIdentity());

    const std::set<std::string> stages = {"dfg-lut",          "environment", "sun-extract",
                                          "sun-in-probe",     "specular-ld", "diffuse-sh",
                                          "irradiance-cube",  "probe-ld",    "gltf-export",
                                          "material-preview", "light-card",  "preview-reference"};
    std::set<std::string> stagesAndManifest = stages;
    stagesAndManifest.insert("manifest");
    const std::map<std::string, std::set<std::string>> reached = {
        // The LD kernel: both LD chains. The glTF export re-filters with the LD chain's code; the
        // sun-in-probe check bakes the shipped probe. The bright-texel list's layout reaches the irradiance
        // kernel too, which integrates the same list.
        {"kernels/ld.h", {"specular-ld", "probe-ld", "gltf-export", "sun-in-probe"}},
        {"kernels/bright_list.h",
         {"specular-ld", "probe-ld", "irradiance-cube", "gltf-export", "sun-in-probe"}},
        {"kernels/dfg.h", {"dfg-lut", "sun-in-probe"}},
        {"kernels/cube.h", stagesAndManifest}, // the face convention: ingest, every kernel, the cube headers
        {"baker/src/stages/sh_projection.cpp", {"diffuse-sh", "sun-in-probe"}},
        {"baker/src/ingest/ingest.cpp", {"environment", "probe-ld"}},
        {"baker/src/scene/scene_stages.cpp", stages}, // the stage runner
        {"baker/src/scene/scene_manifest.cpp", {"manifest"}},
    };
    for (const auto& [file, kinds] : reached) {
        sources.append(file, "\n// an edited comment\n");
        EXPECT_EQ(changedKinds(unchanged, sources.identity()), kinds) << file;
        sources.restore(file);
    }
    EXPECT_EQ(sources.identity(), unchanged); // reverted: every identity is back

    // And through the keys: an LD-kernel edit re-runs the LD stages and what reads them, not the DFG LUT or
    // the irradiance cube.
    sources.append("kernels/ld.h", "\n// an edited comment\n");
    const ibl::Plan plan = everyKindPlan();
    const Keys inputs = fakeInputHashes(plan);
    const std::set<std::string> changed =
        changedIds(ibl::planStageKeys(plan, inputs, "opencl", unchanged),
                   ibl::planStageKeys(plan, inputs, "opencl", sources.identity()));
    // (gltf and preview read the specular chain.)
    EXPECT_EQ(changed, (std::set<std::string>{"specular", "probe:pavilion", "gltf", "preview"}));
}

// manifest.json is written by every bake that is not up to date; it records its writer's code so that the
// up-to-date check does not keep one that other code wrote.
TEST(StageCodeIdentity, ManifestFromOtherCodeIsNotUpToDate) {
    const fs::path dir = ibl::test::freshTempDir("stage-code-manifest");
    ibl::test::writeLatLong(dir / "env.hdr", 0.5f);
    const nlohmann::json sceneJson = {
        {"environment", {{"file", "env.hdr"}}},
        {"materials", {{"specular", false}}},
        {"outputs", {{"directory", "out"}, {"quality", "draft"}, {"faceSize", 16}}}};
    const ibl::Scene scene = ibl::parseScene(sceneJson.dump(), "scene.json", dir);
    ibl::BakeOptions options;
    options.backend = ibl::Backend::Cpu;
    ibl::ProgressSink silent;
    ASSERT_TRUE(ibl::bakeScene(scene, options, silent).ok);
    EXPECT_TRUE(ibl::checkBakeUpToDate(scene, options).upToDate);

    const fs::path manifestFile = dir / "out" / "manifest.json";
    nlohmann::json manifest = nlohmann::json::parse(std::ifstream(manifestFile));
    EXPECT_EQ(manifest.at("manifestCode"), ibl::builtInStageCodeIdentity().at("manifest"));
    manifest["manifestCode"] = "other";
    ibl::test::writeText(manifestFile, manifest.dump(2) + "\n");
    const ibl::UpToDate checked = ibl::checkBakeUpToDate(scene, options);
    EXPECT_FALSE(checked.upToDate);
    EXPECT_EQ(checked.reason, "manifest.json was written by other code");

    // The stages are still current: a bake reuses every entry and writes this code's manifest.
    const ibl::BakeSummary rebaked = ibl::bakeScene(scene, options, silent);
    ASSERT_TRUE(rebaked.ok) << rebaked.error;
    for (const ibl::StageResult& stage : rebaked.stages)
        EXPECT_EQ(stage.status, ibl::StageStatus::Cached) << stage.id;
    EXPECT_TRUE(ibl::checkBakeUpToDate(scene, options).upToDate);
    fs::remove_all(dir);
}

} // namespace
