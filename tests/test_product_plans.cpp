// The single-product commands as plans of a scene's stages (iblbake/baker/product_plans.h), in process: the
// stage kinds are the scene's, the chain's every level and the sun's light are the scene bake's for the same
// settings, and a run leaves nothing behind but its files (no private cache, no file when it fails).
#include "cli_runner.h"
#include "scene_bake_support.h"

#include <iblbake/baker/bake_scene.h>
#include <iblbake/baker/product_plans.h>
#include <iblbake/core/error.h>
#include <iblbake/ktx2/ktx2.h>
#include <iblbake/scene/scene.h>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cstdlib>
#include <filesystem>
#include <set>
#include <string>

namespace fs = std::filesystem;
using namespace ibl;
using namespace ibl::test;

namespace {

const fs::path kSample = fs::path(IBLBAKE_SOURCE_DIR) / "data" / "rooitou_park_1k.hdr";

// The sample, 32-px faces, calibrated to a 100,000-lux sun taken out as a disk light, as a command's job.
EnvironmentJob sampleWithSunOut(const fs::path& sunJson) {
    EnvironmentJob e;
    e.files = {kSample};
    e.faceSize = 32;
    e.calibration.source = CalibrationSource::SunIlluminance;
    e.calibration.value = 100000.0;
    e.extractSun = true;
    e.sunMaxSolidAngle = SunDetectSettings{}.maxSolidAngle;
    e.sunJson = sunJson;
    return e;
}

SpecularJob draftChain(const fs::path& file) {
    SpecularJob job;
    job.settings.quality = Quality::Draft;
    job.chain = file;
    return job;
}

// The system's temporary directory, pointed at a fresh one for the test's life (runProductPlan's private
// cache goes there).
class TemporaryDirectory {
  public:
    explicit TemporaryDirectory(const fs::path& dir) : dir_(dir) {
        if (const char* old = std::getenv("TMPDIR")) old_ = old;
        fs::create_directories(dir_);
        ::setenv("TMPDIR", dir_.c_str(), 1);
    }
    ~TemporaryDirectory() {
        if (old_.empty())
            ::unsetenv("TMPDIR");
        else
            ::setenv("TMPDIR", old_.c_str(), 1);
    }
    bool empty() const { return fs::is_empty(dir_); }

  private:
    fs::path dir_;
    std::string old_;
};

TEST(ProductPlans, CommandsRunTheStageKindsOfAScene) {
    const ProductPlan specular = specularPlan(sampleWithSunOut("sun.json"), draftChain("chain.ktx2"), "cpu");
    std::vector<std::string> kinds;
    for (const PlanStage& s : specular.plan.stages)
        kinds.push_back(s.kind);
    EXPECT_EQ(kinds, (std::vector<std::string>{"environment", "sun-extract", "specular-ld"}));

    const nlohmann::json sceneJson = {{"environment", {{"file", kSample.string()}, {"extractSun", true}}},
                                      {"outputs", {{"directory", "out"}, {"faceSize", 32}}}};
    std::set<std::string> sceneKinds;
    for (const PlanStage& s : planScene(parseScene(sceneJson.dump(), "scene.json", ".")).stages)
        sceneKinds.insert(s.kind);
    for (const std::string& kind : kinds)
        EXPECT_TRUE(sceneKinds.count(kind)) << kind << " is not a stage kind of the scene's plan";
    const ProductPlan dfg = dfgPlan(DfgSettings{}, DfgLutFile::ExrHalf, "lut.exr", "cpu");
    ASSERT_EQ(dfg.plan.stages.size(), 1u);
    EXPECT_EQ(dfg.plan.stages[0].kind, "dfg-lut");
    EXPECT_TRUE(sceneKinds.count("dfg-lut"));
}

TEST(ProductPlans, SpecularIsTheScenesChainLevelByLevelAndTheScenesSun) {
    const fs::path dir = freshTempDir("product_plans_scene");
    const TemporaryDirectory tmp(dir / "tmp");
    const Executor cpu = Executor::cpu();
    const ProductRun run = runProductPlan(
        specularPlan(sampleWithSunOut(dir / "sun.json"), draftChain(dir / "chain.ktx2"), "cpu"),
        [&] { return &cpu; });
    EXPECT_TRUE(tmp.empty()) << "the private cache is removed";
    EXPECT_GT(run.stageSeconds("specular"), 0.0);

    const nlohmann::json scene = {
        {"environment",
         {{"file", kSample.string()}, {"calibration", {{"sunIlluminance", 100000}}}, {"extractSun", true}}},
        {"outputs", {{"directory", "out"}, {"quality", "draft"}, {"faceSize", 32}, {"dfgSize", 16}}}};
    const BakeSummary summary = bakeSceneJson(dir, scene);
    ASSERT_TRUE(summary.ok) << summary.error;

    const Ktx2Image command = readKtx2(dir / "chain.ktx2"), baked = readKtx2(dir / "out" / "specular.ktx2");
    ASSERT_EQ(command.levels.size(), baked.levels.size());
    for (std::size_t m = 0; m < command.levels.size(); ++m)
        for (std::size_t f = 0; f < 6; ++f)
            EXPECT_EQ(command.levels[m][f].pixels, baked.levels[m][f].pixels)
                << "level " << m << " face " << f;
    EXPECT_EQ(command.keyValues.at("iblbake.sunLight"), baked.keyValues.at("iblbake.sunLight"));
    EXPECT_EQ(readBytes(dir / "sun.json"), readBytes(dir / "out" / "sun.json"));
    fs::remove_all(dir);
}

TEST(ProductPlans, AFailedRunLeavesNoFileAndNoPrivateCache) {
    const fs::path dir = freshTempDir("product_plans_failure");
    const TemporaryDirectory tmp(dir / "tmp");
    const Executor cpu = Executor::cpu();
    EnvironmentJob missing = sampleWithSunOut(dir / "sun.json");
    missing.files = {dir / "missing.hdr"};
    EXPECT_THROW(
        runProductPlan(specularPlan(missing, draftChain(dir / "chain.ktx2"), "cpu"), [&] { return &cpu; }),
        Error);
    // A sky without a sun: the sun stage fails after the environment stage ran.
    EnvironmentJob sunless = sampleWithSunOut(dir / "sun.json");
    sunless.calibration = {};
    writeLatLong(dir / "sky.exr", 0.5f);
    sunless.files = {dir / "sky.exr"};
    try {
        runProductPlan(specularPlan(sunless, draftChain(dir / "chain.ktx2"), "cpu"), [&] { return &cpu; });
        ADD_FAILURE() << "a sky without a sun ran";
    } catch (const SettingError& e) { // the command names its flag (--extract-sun) and the file is in front
        EXPECT_EQ(e.setting(), "extractSun");
        EXPECT_NE(std::string(e.what()).find((dir / "sky.exr").string() + ": no sun detected"),
                  std::string::npos)
            << e.what();
    }
    EXPECT_FALSE(fs::exists(dir / "chain.ktx2"));
    EXPECT_FALSE(fs::exists(dir / "sun.json"));
    EXPECT_TRUE(tmp.empty()) << "the private cache is removed";
    fs::remove_all(dir);
}

} // namespace
