// The product module (iblbake/baker/products.h), the mip-mapping header (kernels/mip_mapping.h) and the KTX2
// format names: one source for each, machine-readable values in files, readers of older files.
#include "cli_runner.h"
#include "scene_test_support.h"

#include <iblbake/baker/bake_scene.h>
#include <iblbake/baker/products.h>
#include <iblbake/baker/specular.h>
#include <iblbake/core/error.h>
#include <iblbake/ktx2/ktx2.h>
#include <iblbake/runtime/runtime.h>
#include <iblbake/scene/scene.h>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <set>

namespace fs = std::filesystem;
using nlohmann::json;
using namespace ibl;
using namespace ibl::test;

namespace {

const std::string kSample = std::string(IBLBAKE_SOURCE_DIR) + "/data/rooitou_park_1k.hdr";

std::string errorOf(const std::function<void()>& f) {
    try {
        f();
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

// Every key path of a document ("sh.window.name"); array elements are not descended into.
void keyPaths(const json& doc, const std::string& prefix, std::set<std::string>& out) {
    if (!doc.is_object()) return;
    for (const auto& [key, value] : doc.items()) {
        out.insert(prefix + key);
        keyPaths(value, prefix + key + ".", out);
    }
}

json readJson(const fs::path& file) {
    return json::parse(readText(file));
}

CubeMap flatCube(int n) {
    CubeMap cube(n);
    for (ImageRGBA& face : cube.faces)
        face.pixels.assign(std::size_t(n) * std::size_t(n), glm::vec4(0.5f, 0.6f, 0.7f, 1.0f));
    return cube;
}

} // namespace

TEST(MipMappingHeader, RoughnessLevelRoundTripAndLevelCount) {
    for (MipMapping mapping : {MipMapping::Frostbite, MipMapping::Linear})
        for (int levels : {2, 5, 9, 14})
            for (int m = 0; m < levels; ++m) {
                const float r = perceptualRoughnessForLevel(m, levels, mapping);
                EXPECT_NEAR(mipLevelForRoughness(std::uint32_t(mapping), r, std::uint32_t(levels)), float(m),
                            1e-4f)
                    << mipMappingName(mapping) << " L=" << levels << " m=" << m;
            }
    EXPECT_FLOAT_EQ(perceptualRoughnessForLevel(2, 5, MipMapping::Frostbite), 0.25f);
    EXPECT_FLOAT_EQ(perceptualRoughnessForLevel(2, 5, MipMapping::Linear), 0.5f);
    EXPECT_FLOAT_EQ(perceptualRoughnessForLevel(0, 1, MipMapping::Linear), 0.0f);
    // Roughness beyond [0, 1] is clamped to the chain.
    EXPECT_FLOAT_EQ(mipLevelForRoughness(IBL_MIP_FROSTBITE, 2.0f, 9u), 8.0f);
    EXPECT_EQ(mipLevelCount(1), 1);
    EXPECT_EQ(mipLevelCount(2), 2);
    EXPECT_EQ(mipLevelCount(255), 8);
    EXPECT_EQ(mipLevelCount(256), 9);
    EXPECT_EQ(mipLevelCount(8192), 14);
    // The bake's chain and the scene plan count the same levels.
    EXPECT_EQ(levelCountFor(256, SpecularSettings{}), mipLevelCount(256));
}

TEST(MipMappingHeader, StoredValuesNewAndOldLoad) {
    EXPECT_EQ(parseStoredMipMapping("frostbite"), MipMapping::Frostbite);
    EXPECT_EQ(parseStoredMipMapping("linear"), MipMapping::Linear);
    // The prose every writer stored before the bare name (specular_command.cpp, scene_stages.cpp).
    EXPECT_EQ(parseStoredMipMapping("frostbite: level m of L holds perceptualRoughness (m/(L-1))^2"),
              MipMapping::Frostbite);
    EXPECT_EQ(parseStoredMipMapping("linear: level m of L holds perceptualRoughness m/(L-1)"),
              MipMapping::Linear);

    const fs::path dir = freshTempDir("products_mapping");
    CubeMapChain chain = bakeSpecular(flatCube(8), SpecularSettings{}, Executor::cpu());
    for (const auto& [value, expected] : std::vector<std::pair<std::string, MipMapping>>{
             {"linear", MipMapping::Linear},
             {"linear: level m of L holds perceptualRoughness m/(L-1)", MipMapping::Linear},
             {"frostbite", MipMapping::Frostbite},
             {"frostbite: level m of L holds perceptualRoughness (m/(L-1))^2", MipMapping::Frostbite}}) {
        writeKtx2Cube(dir / "ld.ktx2", chain, Ktx2Format::RGBA32F, {{"iblbake.roughnessMapping", value}});
        EXPECT_EQ(loadLdKtx2(dir / "ld.ktx2").mapping, expected) << value;
    }
    fs::remove_all(dir);
}

TEST(MipMappingHeader, BadNamesAreOneLineErrors) {
    EXPECT_EQ(errorOf([] { parseMipMapping("cubic"); }), "'cubic' is not one of frostbite, linear");
    // A name is exact; only stored values may carry the old prose.
    EXPECT_NE(errorOf([] { parseMipMapping("linear: level m"); }), "");
    const std::string stored = errorOf([] { parseStoredMipMapping("cubic: level m\nof L"); });
    EXPECT_NE(stored.find("'cubic: level m\\x0Aof L'"), std::string::npos) << stored;
    EXPECT_EQ(stored.find('\n'), std::string::npos);

    const fs::path dir = freshTempDir("products_bad_mapping");
    writeKtx2Cube(dir / "ld.ktx2", bakeSpecular(flatCube(4), SpecularSettings{}, Executor::cpu()),
                  Ktx2Format::RGBA32F, {{"iblbake.roughnessMapping", "cubic"}});
    const std::string loaded = errorOf([&] { loadLdKtx2(dir / "ld.ktx2"); });
    EXPECT_NE(loaded.find("ld.ktx2"), std::string::npos) << loaded;
    EXPECT_NE(loaded.find("'cubic'"), std::string::npos) << loaded;
    EXPECT_EQ(loaded.find('\n'), std::string::npos);
    CliRun r =
        runCli("specular " + kSample + " --size 16 --mip-mapping cubic -o " + (dir / "x.ktx2").string());
    EXPECT_NE(r.exitCode, 0); // a CLI11 parse error
    EXPECT_EQ(lineCount(r.err), 1) << r.err;
    EXPECT_NE(r.err.find("--mip-mapping"), std::string::npos) << r.err;
    fs::remove_all(dir);
}

TEST(Ktx2FormatNames, OneTableAndOneParser) {
    for (std::size_t i = 0; i < kKtx2FormatNames.size(); ++i)
        EXPECT_EQ(parseKtx2Format(kKtx2FormatNames[i]), Ktx2Format(i));
    EXPECT_EQ(errorOf([] { parseKtx2Format("rgba8"); }),
              "'rgba8' is not one of rgba16f, rgba32f, b10g11r11, e5b9g9r9, bc6h, bc6h-fast, bc6h-best");
}

TEST(Products, LdChainKeysStoreTheMappingByName) {
    LdChainProduct ld;
    ld.mapping = MipMapping::Linear;
    ld.levelCount = 5;
    ld.colorSpace = "lin_rec709";
    std::map<std::string, std::string> kv;
    for (const auto& [key, value] : ldChainKeyValues(ld, CalibrationRecord{}, std::nullopt))
        kv[key] = value;
    EXPECT_EQ(kv.at("iblbake.roughnessMapping"), "linear");
    EXPECT_EQ(kv.at("iblbake.roughnessMappingMeaning"), mipMappingMeaning(MipMapping::Linear));
    EXPECT_EQ(kv.at("iblbake.sun"), "kept in the environment");
    EXPECT_EQ(kv.count("iblbake.sunInLevel0"), 0u);
}

TEST(Products, CalibrationRecordRoundTripsTyped) {
    CalibrationRecord r;
    r.factor = 16338.977812345;
    r.source = CalibrationSource::SunIlluminance;
    r.sourceValue = 1e5;
    r.quantity = "sun illuminance (perpendicular)";
    r.measuredBefore = 6.12;
    r.measuredAfter = 1e5;
    r.sunMeasured = r.sunFound = true;
    r.sunIlluminanceBefore = 6.12;
    r.sunIlluminanceAfter = 1e5;
    const CalibrationRecord back = calibrationRecordFromJson(json::parse(calibrationRecordToJson(r).dump()));
    EXPECT_EQ(calibrationMetadata(back, ""), calibrationMetadata(r, ""));
    EXPECT_EQ(back.factor, r.factor);
    EXPECT_NE(errorOf([] { calibrationRecordFromJson(json::object()); }), "");
}

// An uncalibrated map's sun is in the map's relative units, wherever it is written (issue 12, item 8).
TEST(SunLabel, FollowsTheCalibrationInEveryProduct) {
    DiskLight sun;
    sun.illuminance = 6.12;
    CalibrationRecord relative, absolute;
    absolute.source = CalibrationSource::Scale;
    absolute.factor = absolute.sourceValue = 2.0;
    for (const auto& [record, units] : {std::pair{relative, "relative"}, std::pair{absolute, "lux"}}) {
        EXPECT_EQ(json::parse(sunJson(sun, record)).at("units"), units);
        std::map<std::string, std::string> kv;
        for (const auto& [key, value] : calibrationKeyValues(record, sun))
            kv[key] = value;
        EXPECT_EQ(json::parse(kv.at("iblbake.sunLight")).at("units"), units);
        const json doc =
            diffuseDocument(bakeDiffuseSH(flatCube(4), {}), "auto", "lin_rec709", {}, record, sun);
        EXPECT_EQ(doc.at("calibration").at("sunLight").at("units"), units);
    }
}

TEST(SunLabel, UncalibratedDiffuseCommandWritesRelativeUnits) {
    const fs::path dir = freshTempDir("products_sun_label");
    CliRun r = runCli("diffuse " + kSample + " --size 64 --extract-sun -o " + (dir / "d.json").string() +
                      " --sun-json " + (dir / "s.json").string());
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(readJson(dir / "s.json").at("units"), "relative");
    const json doc = readJson(dir / "d.json");
    EXPECT_EQ(doc.at("units"), "relative (input values, uncalibrated)");
    EXPECT_EQ(doc.at("calibration").at("sunLight").at("units"), "relative");
    fs::remove_all(dir);
}

// `iblbake diffuse` and a scene bake run the same stage: of the same environment and settings, the same
// document, byte for byte.
TEST(DiffuseDocument, CommandAndSceneStageWriteTheSameDocument) {
    const fs::path dir = freshTempDir("products_diffuse_schema");
    writeLatLong(dir / "env.hdr", 0.5f);
    writeText(dir / "scene.json",
              json{{"environment", {{"file", "env.hdr"}}},
                   {"materials", {{"specular", false}}},
                   {"outputs", {{"directory", "out"}, {"quality", "draft"}, {"faceSize", 16}}}}
                  .dump());
    BakeOptions options;
    options.backend = Backend::Cpu;
    ProgressSink silent;
    const BakeSummary summary = bakeScene(loadSceneFile(dir / "scene.json"), options, silent);
    ASSERT_TRUE(summary.ok) << summary.error;
    CliRun r = runCli("diffuse " + (dir / "env.hdr").string() + " --size 16 -o " + (dir / "d.json").string());
    ASSERT_EQ(r.exitCode, 0) << r.err;

    EXPECT_EQ(readText(dir / "d.json"), readText(dir / "out" / "diffuse.json"));
    std::set<std::string> scene;
    keyPaths(readJson(dir / "out" / "diffuse.json"), "", scene);
    EXPECT_TRUE(scene.count("calibration.sun"));
    EXPECT_TRUE(scene.count("sh.irradianceOverPi"));
    fs::remove_all(dir);
}
