// prepareEnvironment (iblbake/baker/environment.h) in process: it is the separate steps bit for bit, its
// errors name the setting and no CLI flag, the cube with the sun is kept only when asked, and the CLI and a
// scene bake prepare the same environment from the same settings.
#include "cli_runner.h"
#include "scene_bake_support.h"

#include <iblbake/baker/bake_scene.h>
#include <iblbake/baker/calibration.h>
#include <iblbake/baker/environment.h>
#include <iblbake/baker/ingest.h>
#include <iblbake/baker/sun.h>
#include <iblbake/core/error.h>
#include <iblbake/ktx2/ktx2.h>
#include <iblbake/scene/scene.h>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cstring>
#include <filesystem>
#include <string>

namespace fs = std::filesystem;
using namespace ibl;
using namespace ibl::test;

namespace {

const fs::path kSample = fs::path(IBLBAKE_SOURCE_DIR) / "data" / "rooitou_park_1k.hdr";

bool sameBits(const CubeMap& a, const CubeMap& b) {
    if (a.faceSize != b.faceSize) return false;
    for (std::size_t f = 0; f < 6; ++f)
        if (std::memcmp(a.faces[f].pixels.data(), b.faces[f].pixels.data(),
                        a.faces[f].pixels.size() * sizeof(a.faces[f].pixels[0])) != 0)
            return false;
    return true;
}

EnvironmentSettings sunIlluminance(int faceSize, SunExtraction sun) {
    EnvironmentSettings s;
    s.ingest.sourceFaceSize = faceSize;
    s.calibration.source = CalibrationSource::SunIlluminance;
    s.calibration.value = 100000.0;
    s.sun = sun;
    return s;
}

// A sky without a sun: the same value everywhere.
SourceEnvironment flatSky() {
    SourceEnvironment env;
    env.cube = CubeMap(16);
    for (ImageRGBA& face : env.cube.faces)
        for (glm::vec4& p : face.pixels)
            p = glm::vec4(1.0f);
    env.report.file = "flat.exr";
    env.report.workingColorSpace = "lin_rec709";
    return env;
}

void expectNoFlag(const std::string& message) {
    EXPECT_EQ(message.find("--"), std::string::npos) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
}

} // namespace

TEST(PrepareEnvironment, IsTheSeparateStepsBitForBit) {
    EnvironmentSettings settings = sunIlluminance(64, SunExtraction::Required);
    settings.keepCubeWithSun = true;
    const PreparedEnvironment prepared = prepareEnvironment({kSample}, settings);

    SourceEnvironment env = ingestEnvironment({kSample}, settings.ingest);
    CalibrationSettings calibration = settings.calibration;
    calibration.luminanceWeights = workingLuminanceWeights(env.report.workingColorSpace);
    const CalibrationRecord record = computeCalibration(env.cube, calibration);
    applyCalibration(env.cube, record.factor);
    const CubeMap withSun = env.cube;
    SunDetectSettings detection;
    detection.luminanceWeights = calibration.luminanceWeights;
    const SunDetection sun = detectSun(env.cube, detection);
    ASSERT_TRUE(sun.found) << sun.reason;
    const DiskLight light = extractSun(env.cube, sun, detection.luminanceWeights);

    EXPECT_EQ(prepared.record.factor, record.factor);
    EXPECT_EQ(prepared.record.measuredAfter, record.measuredAfter);
    EXPECT_EQ(prepared.env.report.file, env.report.file);
    EXPECT_TRUE(sameBits(prepared.env.cube, env.cube));
    ASSERT_TRUE(prepared.withSun);
    EXPECT_TRUE(sameBits(*prepared.withSun, withSun));
    ASSERT_TRUE(prepared.sun);
    EXPECT_EQ(prepared.sun->illuminance, light.illuminance);
    EXPECT_EQ(prepared.sun->direction, light.direction);
}

TEST(PrepareEnvironment, WithSunOnlyWhenAskedAndASunTakenOut) {
    const PreparedEnvironment extracted =
        prepareEnvironment({kSample}, sunIlluminance(32, SunExtraction::Required));
    EXPECT_TRUE(extracted.sun);
    EXPECT_FALSE(extracted.withSun);

    EnvironmentSettings kept = sunIlluminance(32, SunExtraction::Keep);
    kept.keepCubeWithSun = true;
    const PreparedEnvironment keptSun = prepareEnvironment({kSample}, kept);
    EXPECT_FALSE(keptSun.sun);
    EXPECT_FALSE(keptSun.withSun);
    // The factor is measured before the extraction, so keeping the sun does not change it.
    EXPECT_EQ(keptSun.record.factor, extracted.record.factor);

    EnvironmentSettings none;
    none.sun = SunExtraction::IfDetected;
    none.keepCubeWithSun = true;
    const PreparedEnvironment flat = prepareEnvironment(flatSky(), none);
    EXPECT_FALSE(flat.sun);
    EXPECT_FALSE(flat.withSun);
}

TEST(PrepareEnvironment, ErrorsNameTheSettingAndTheFileButNoFlag) {
    EnvironmentSettings extract;
    extract.sun = SunExtraction::Required;
    try {
        prepareEnvironment(flatSky(), extract);
        ADD_FAILURE() << "a flat sky gave a sun";
    } catch (const SettingError& e) {
        EXPECT_EQ(e.setting(), "extractSun");
        EXPECT_EQ(std::string(e.what()).rfind("flat.exr: no sun detected: ", 0), 0u) << e.what();
        expectNoFlag(e.what());
    }
    try {
        prepareEnvironment(flatSky(), sunIlluminance(16, SunExtraction::Keep));
        ADD_FAILURE() << "a flat sky was calibrated by its sun";
    } catch (const SettingError& e) {
        EXPECT_EQ(e.setting(), "calibration");
        EXPECT_NE(std::string(e.what()).find("no sun detected"), std::string::npos) << e.what();
        expectNoFlag(e.what());
    }
    EnvironmentSettings badSize;
    badSize.ingest.sourceFaceSize = -4;
    try {
        prepareEnvironment({kSample}, badSize);
        ADD_FAILURE() << "face size -4 was accepted";
    } catch (const SettingError& e) {
        EXPECT_EQ(e.setting(), "sourceFaceSize");
        expectNoFlag(e.what());
    }
    try {
        parseLayout("spherical");
        ADD_FAILURE() << "layout 'spherical' was accepted";
    } catch (const SettingError& e) {
        EXPECT_EQ(e.setting(), "layout");
        expectNoFlag(e.what());
    }
}

// Each caller puts its own name for the setting in front: the flag, or the scene key path.
TEST(PrepareEnvironment, CallersNameTheSettingTheirWay) {
    const fs::path dir = freshTempDir("prepare_errors");
    writeLatLong(dir / "sky.hdr", 0.5f); // a gradient, no sun
    const CliRun cli = runCli("specular " + (dir / "sky.hdr").string() +
                              " --size 8 --sun-illuminance 100000 -o " + (dir / "x.ktx2").string());
    EXPECT_NE(cli.exitCode, 0);
    EXPECT_NE(cli.err.find("--sun-illuminance: " + (dir / "sky.hdr").string() + ": no sun detected"),
              std::string::npos)
        << cli.err;

    const nlohmann::json scene = {
        {"environment", {{"file", "sky.hdr"}, {"calibration", {{"sunIlluminance", 100000}}}}},
        {"outputs", {{"directory", "out"}, {"quality", "draft"}, {"faceSize", 16}, {"dfgSize", 16}}}};
    writeText(dir / "sky.json", scene.dump());
    BakeOptions options;
    options.backend = Backend::Cpu;
    ProgressSink silent;
    const BakeSummary summary = bakeScene(loadSceneFile(dir / "sky.json"), options, silent);
    EXPECT_FALSE(summary.ok);
    EXPECT_NE(summary.error.find("sky.json: environment.calibration.sunIlluminance: "), std::string::npos)
        << summary.error;
    EXPECT_NE(summary.error.find("no sun detected"), std::string::npos) << summary.error;
    expectNoFlag(summary.error);
    fs::remove_all(dir);
}

// `iblbake specular` and a scene bake given the same input and calibration: the same factor and the same
// calibrated source cube (the specular chain's level 0, the unconvolved source).
TEST(PrepareEnvironment, CliAndSceneBakePrepareTheSameCube) {
    const fs::path dir = freshTempDir("prepare_same");
    const fs::path cliKtx = dir / "cli.ktx2";
    const CliRun cli =
        runCli("specular " + kSample.string() +
               " --size 32 --quality draft --backend cpu --sun-illuminance 100000 -o " + cliKtx.string());
    ASSERT_EQ(cli.exitCode, 0) << cli.err;

    const nlohmann::json scene = {
        {"environment", {{"file", kSample.string()}, {"calibration", {{"sunIlluminance", 100000}}}}},
        {"outputs", {{"directory", "out"}, {"quality", "draft"}, {"faceSize", 32}, {"dfgSize", 16}}}};
    const BakeSummary summary = bakeSceneJson(dir, scene);
    ASSERT_TRUE(summary.ok) << summary.error;

    const Ktx2Image fromCli = readKtx2(cliKtx), fromScene = readKtx2(dir / "out" / "specular.ktx2");
    EXPECT_EQ(fromCli.keyValues.at("iblbake.calibration.factor"),
              fromScene.keyValues.at("iblbake.calibration.factor"));
    ASSERT_FALSE(fromCli.levels.empty());
    ASSERT_FALSE(fromScene.levels.empty());
    ASSERT_EQ(fromCli.pixelWidth, fromScene.pixelWidth);
    for (std::size_t f = 0; f < 6; ++f)
        EXPECT_EQ(fromCli.levels[0][f].pixels, fromScene.levels[0][f].pixels) << "face " << f;
    fs::remove_all(dir);
}
