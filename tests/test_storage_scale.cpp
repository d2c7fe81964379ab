// Float storage (docs/conventions.md "Float storage and the storage scale", issue 13 item 4): a product whose
// values exceed its format is stored times a recorded power of two (KTX2 "iblbake.storageScale") that every
// reader divides out; clamping happens only on request and reports the energy lost.
#include "cli_runner.h"
#include "runtime_test_support.h"
#include "test_support.h"

#include <iblbake/baker/environment.h>
#include <iblbake/baker/products.h>
#include <iblbake/baker/sh.h>
#include <iblbake/baker/specular.h>
#include <iblbake/core/error.h>
#include <iblbake/ktx2/ktx2.h>
#include <iblbake/ktx2/storage_scale.h>
#include <iblbake/runtime/runtime.h>
#include <iblbake/scene/scene.h>
#include <iblbake/scene/scene_plan.h>

#include "stage_keys.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <set>
#include <unistd.h>

namespace {

namespace fs = std::filesystem;
using namespace ibl;
using rt_test::makeCube;
using rt_test::openclOrCpu;
using test::CliRun;
using test::kSampleHdri;
using test::runCli;

fs::path testDir(const std::string& name) {
    const fs::path dir =
        fs::temp_directory_path() / ("iblbake_storage_" + name + "_" + std::to_string(::getpid()));
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir;
}

// The levels of a KTX2 cube as radiance (divided by its storage scale, as every reader does).
std::vector<CubeMap> radianceLevels(const fs::path& file) {
    Ktx2Image image = readKtx2(file);
    unscaleKtx2Texels(image);
    std::vector<CubeMap> levels;
    for (const std::vector<ImageRGBA>& faces : image.levels) {
        CubeMap level(faces.at(0).width);
        for (int f = 0; f < 6; ++f)
            level.faces[f] = faces[std::size_t(f)];
        levels.push_back(std::move(level));
    }
    return levels;
}

// The test's own energy of a level: sum of R + G + B times each texel's exact solid angle.
struct LevelCheck {
    double energy = 0.0;
    std::uint64_t nonFinite = 0, atHalfMax = 0;
};
LevelCheck checkLevel(const CubeMap& level, float storedHalfMax = 0.0f) {
    LevelCheck out;
    for (int f = 0; f < 6; ++f)
        for (int y = 0; y < level.faceSize; ++y)
            for (int x = 0; x < level.faceSize; ++x) {
                const glm::vec4& t = level.faces[f].at(x, y);
                for (int c = 0; c < 3; ++c) {
                    if (!std::isfinite(t[c])) ++out.nonFinite;
                    if (storedHalfMax > 0.0f && t[c] >= storedHalfMax) ++out.atHalfMax;
                    out.energy += double(t[c]) * texelSolidAngle(x, y, level.faceSize);
                }
            }
    return out;
}

// ------------------------------------------------------------------------------------------------
// The default park bake (data/scenes/park.json: rooitou_park_1k.hdr, sun calibrated to 100,000 lux and
// extracted, rgba16f, production, 256-px faces, roughness max 0.8), through the library flow of the scene's
// specular stage, stored as rgba16f and as rgba32f.

TEST(StorageScale, ParkBakeKeepsEveryLevelsEnergyInHalfFloats) {
    const auto start = std::chrono::steady_clock::now();
    const fs::path dir = testDir("park");
    EnvironmentSettings settings;
    settings.ingest.sourceFaceSize = 256;
    settings.calibration.source = CalibrationSource::SunIlluminance;
    settings.calibration.value = 100000.0;
    settings.sun = SunExtraction::Required;
    settings.keepCubeWithSun = true;
    const PreparedEnvironment park =
        prepareEnvironment({fs::path(IBLBAKE_SOURCE_DIR) / "data/rooitou_park_1k.hdr"}, settings);
    ASSERT_TRUE(park.withSun);
    SpecularSettings specular;
    specular.integratedLevels = lastLevelNeeded(mipLevelCount(256), MipMapping::Frostbite, 0.8) + 1;
    const CubeMapChain residual = bakeSpecular(park.env.cube, specular, openclOrCpu());

    // Before the storage scale: the residual chain written as it was (clamped by the writer), against the
    // rgba32f product whose level 0 keeps the sun.
    CubeMapChain wide = residual;
    ASSERT_TRUE(keepSunInLevel0(wide, *park.withSun, Ktx2Format::RGBA32F));
    writeKtx2Cube(dir / "old16.ktx2", residual, Ktx2Format::RGBA16F, {});
    // Now: both formats keep the sun in level 0; rgba16f is stored with its storage scale.
    CubeMapChain narrow = residual;
    ASSERT_TRUE(keepSunInLevel0(narrow, *park.withSun, Ktx2Format::RGBA16F));
    const ProductStorage storage = chooseProductStorage(narrow, Ktx2Format::RGBA16F, false);
    writeProductCube(dir / "new16.ktx2", narrow, Ktx2Format::RGBA16F, {}, storage);
    writeProductCube(dir / "f32.ktx2", wide, Ktx2Format::RGBA32F, {},
                     chooseProductStorage(wide, Ktx2Format::RGBA32F, false));

    // The scale: the largest power of two that fits the brightest channel (the sun) under 65,504.
    float brightest = 0.0f;
    for (const ImageRGBA& face : narrow.levels[0].faces)
        for (const glm::vec4& t : face.pixels)
            brightest = std::max({brightest, t.r, t.g, t.b});
    EXPECT_LE(brightest * storage.scale, 65504.0);
    EXPECT_GT(brightest * storage.scale * 2.0, 65504.0);
    EXPECT_EQ(std::exp2(std::round(std::log2(storage.scale))), storage.scale);
    EXPECT_EQ(ktx2StorageScale(readKtx2(dir / "new16.ktx2")), storage.scale);
    EXPECT_EQ(ktx2StorageScale(readKtx2(dir / "f32.ktx2")), 1.0);

    const std::vector<CubeMap> f32 = radianceLevels(dir / "f32.ktx2");
    const std::vector<CubeMap> new16 = radianceLevels(dir / "new16.ktx2");
    const std::vector<CubeMap> old16 = radianceLevels(dir / "old16.ktx2");
    Ktx2Image stored = readKtx2(dir / "new16.ktx2"); // as stored, for the clamp count
    std::printf("park: storage scale %.9g (2^%d); per level: energy rgba16f/rgba32f - 1, before -> after\n",
                storage.scale, int(std::lround(std::log2(storage.scale))));
    for (std::size_t m = 0; m < f32.size(); ++m) {
        const double reference = checkLevel(f32[m]).energy;
        const LevelCheck after = checkLevel(new16[m]);
        const double before = checkLevel(old16[m]).energy / reference - 1.0;
        const double difference = after.energy / reference - 1.0;
        std::printf("  level %zu (%3d px): %+.4f%% -> %+.5f%%\n", m, f32[m].faceSize, 100.0 * before,
                    100.0 * difference);
        EXPECT_LE(std::abs(difference), 1e-3) << "level " << m;
        EXPECT_EQ(after.nonFinite, 0u) << "level " << m;
        CubeMap asStored(stored.levels[m][0].width);
        for (int f = 0; f < 6; ++f)
            asStored.faces[f] = stored.levels[m][std::size_t(f)];
        EXPECT_EQ(checkLevel(asStored, 65504.0f).atHalfMax, 0u) << "level " << m << " has clamped texels";
    }
    // Dim texels the scale pushes into fp16's subnormal range (below 2^-14 stored, fewer mantissa bits):
    // their share of level 0's energy bounds what they can lose, against the clamp's 65% before.
    std::uint64_t subnormal = 0;
    double subnormalEnergy = 0.0;
    for (int f = 0; f < 6; ++f)
        for (int y = 0; y < f32[0].faceSize; ++y)
            for (int x = 0; x < f32[0].faceSize; ++x)
                for (int c = 0; c < 3; ++c)
                    if (const float v = stored.levels[0][std::size_t(f)].at(x, y)[c];
                        v > 0.0f && v < 0x1p-14f) {
                        ++subnormal;
                        subnormalEnergy +=
                            double(f32[0].faces[f].at(x, y)[c]) * texelSolidAngle(x, y, f32[0].faceSize);
                    }
    std::printf("  level 0: %llu subnormal channels holding %.2g%% of its energy\n",
                (unsigned long long)subnormal, 100.0 * subnormalEnergy / checkLevel(f32[0]).energy);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::printf("park test: %.1f s\n", seconds);
    fs::remove_all(dir);
}

// ------------------------------------------------------------------------------------------------
// A clamping-sized input: a sky with a 2e7 lobe. The runtime shades the rgba16f file (stored scaled) like
// the rgba32f file within half-float precision.

glm::vec3 blazingSky(glm::vec3 d) {
    const float lobe =
        std::pow(std::max(glm::dot(d, glm::normalize(glm::vec3(0.3f, 0.8f, 0.5f))), 0.0f), 64.0f);
    return rt_test::skyLike(d) * 5000.0f + glm::vec3(2e7f, 1.6e7f, 1.2e7f) * lobe;
}

TEST(StorageScale, RuntimeShadesTheScaledHalfFloatFileLikeTheFloatFile) {
    const fs::path dir = testDir("runtime");
    const CubeMapChain chain = bakeSpecular(makeCube(32, blazingSky), SpecularSettings{}, openclOrCpu());
    const ProductStorage half = chooseProductStorage(chain, Ktx2Format::RGBA16F, false);
    EXPECT_LT(half.scale, 1.0 / 256.0); // 2e7 needs at least 2^-9
    EXPECT_FALSE(half.clamped);
    const Ktx2WriteStats stats = writeProductCube(dir / "ld16.ktx2", chain, Ktx2Format::RGBA16F, {}, half);
    EXPECT_EQ(stats.clampedTexels, 0u);
    EXPECT_EQ(stats.repairedNonFinite, 0u);
    writeProductCube(dir / "ld32.ktx2", chain, Ktx2Format::RGBA32F, {},
                     chooseProductStorage(chain, Ktx2Format::RGBA32F, false));

    const DfgTable dfg = dfgTableFromImage(rt_test::dfgLut());
    const ShCoefficients sh = rt_test::projectIrradianceSH(chain.levels[0]);
    const ProbeSet set16(loadLdKtx2(dir / "ld16.ktx2"), dfg, sh),
        set32(loadLdKtx2(dir / "ld32.ktx2"), dfg, sh);
    std::mt19937 rng(13);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f), u01(0.0f, 1.0f);
    std::vector<ShadingPoint> points;
    for (int i = 0; i < 4000; ++i) {
        const glm::vec3 n = glm::normalize(glm::vec3(u(rng), u(rng), u(rng)) + glm::vec3(0, 1e-3f, 0));
        const glm::vec3 v = glm::normalize(n + glm::vec3(u(rng), u(rng), u(rng)));
        points.push_back(makeShadingPoint(glm::vec3(0.0f), n, v, glm::vec3(0.9f), 1.0f, u01(rng)));
    }
    RuntimeOptions options;
    options.diffuse = false; // the LD chain alone
    const std::vector<glm::vec4> a = evaluateCpu(set16, points, options),
                                 b = evaluateCpu(set32, points, options);
    double worst = 0.0;
    for (std::size_t i = 0; i < points.size(); ++i)
        for (int c = 0; c < 3; ++c)
            worst = std::max(worst, std::abs(double(a[i][c]) - b[i][c]) / std::max(double(b[i][c]), 1.0));
    // Half floats keep 11 significant bits: each fetched texel within 2^-11 relative, and so their blend.
    std::printf("runtime rgba16f (scale %.6g) vs rgba32f: worst relative difference %.3g\n", half.scale,
                worst);
    EXPECT_LE(worst, 1.0 / 2048.0);
    // Without the scale, the same file would have clamped the lobe: its shading would be far off.
    writeKtx2Cube(dir / "clamped16.ktx2", chain, Ktx2Format::RGBA16F, {});
    const ProbeSet clamped(loadLdKtx2(dir / "clamped16.ktx2"), dfg, sh);
    const std::vector<glm::vec4> c = evaluateCpu(clamped, points, options);
    double clampedWorst = 0.0;
    for (std::size_t i = 0; i < points.size(); ++i)
        clampedWorst =
            std::max(clampedWorst, std::abs(double(c[i].r) - b[i].r) / std::max(double(b[i].r), 1.0));
    EXPECT_GT(clampedWorst, 0.5);
    fs::remove_all(dir);
}

// ------------------------------------------------------------------------------------------------
// Clamping on request: scale 1, the writer clamps, and the energy lost is reported. The check is
// independent of the implementation: the energies of the clamped rgba16f file and of the rgba32f file.

TEST(StorageScale, ClampOnRequestReportsTheEnergyItLoses) {
    const fs::path dir = testDir("clamp");
    const CubeMapChain chain = bakeSpecular(makeCube(32, blazingSky), SpecularSettings{}, openclOrCpu());
    const ProductStorage clamp = chooseProductStorage(chain, Ktx2Format::RGBA16F, true);
    EXPECT_TRUE(clamp.clamped);
    EXPECT_EQ(clamp.scale, 1.0);
    ASSERT_EQ(clamp.energyLostPercent.size(), chain.levels.size());
    const Ktx2WriteStats stats = writeProductCube(dir / "ld16.ktx2", chain, Ktx2Format::RGBA16F, {}, clamp);
    EXPECT_GT(stats.clampedTexels, 0u);
    writeKtx2Cube(dir / "ld32.ktx2", chain, Ktx2Format::RGBA32F, {});
    const std::vector<CubeMap> half = radianceLevels(dir / "ld16.ktx2"),
                               full = radianceLevels(dir / "ld32.ktx2");
    const Ktx2Image file = readKtx2(dir / "ld16.ktx2");
    EXPECT_EQ(file.keyValues.at("iblbake.storageScale"), "1");
    ASSERT_TRUE(file.keyValues.count("iblbake.storageClamped"));
    for (std::size_t m = 0; m < chain.levels.size(); ++m) {
        const double lost = 100.0 * (1.0 - checkLevel(half[m]).energy / checkLevel(full[m]).energy);
        std::printf("clamp level %zu: reported %.4f%%, measured from the files %.4f%%\n", m,
                    clamp.energyLostPercent[m], lost);
        // Rounding to half floats moves the energy by ~1e-5 of it besides the clamp.
        EXPECT_NEAR(clamp.energyLostPercent[m], lost, 0.01) << "level " << m;
    }
    EXPECT_GT(clamp.energyLostPercent[0], 1.0);
    // The manifest's record round-trips.
    const ProductStorage back = productStorageFromJson(productStorageToJson(clamp));
    EXPECT_TRUE(back.clamped);
    EXPECT_EQ(back.energyLostPercent, clamp.energyLostPercent);
    fs::remove_all(dir);
}

// ------------------------------------------------------------------------------------------------
// Readers: files without the key (older iblbake) are scale 1; a damaged value is an error naming the file.

TEST(StorageScale, FilesWithoutTheKeyLoadWithScaleOne) {
    const fs::path dir = testDir("old");
    CubeMapChain chain;
    chain.levels.push_back(makeCube(4, rt_test::skyLike));
    writeKtx2Cube(dir / "old.ktx2", chain, Ktx2Format::RGBA16F, {});
    const Ktx2Image old = readKtx2(dir / "old.ktx2");
    EXPECT_EQ(old.keyValues.count(kStorageScaleKey), 0u);
    EXPECT_EQ(ktx2StorageScale(old), 1.0);
    Ktx2Image unscaled = old;
    unscaleKtx2Texels(unscaled);
    EXPECT_EQ(unscaled.levels[0][0].pixels, old.levels[0][0].pixels);
    EXPECT_EQ(loadIrradianceKtx2(dir / "old.ktx2").faces[2].pixels, old.levels[0][2].pixels);

    // The same texels stored at 2^-3 load back exactly (a power of two changes only the exponent).
    ProductStorage eighth;
    eighth.scale = 0.125;
    writeProductCube(dir / "eighth.ktx2", chain, Ktx2Format::RGBA32F, {}, eighth);
    EXPECT_EQ(readKtx2(dir / "eighth.ktx2").keyValues.at(kStorageScaleKey), "0.125");
    EXPECT_EQ(loadIrradianceKtx2(dir / "eighth.ktx2").faces[2].pixels, chain.levels[0].faces[2].pixels);

    for (const char* bad : {"0", "-1", "inf", "nan", "0.5x", ""}) {
        writeKtx2Cube(dir / "bad.ktx2", chain, Ktx2Format::RGBA16F, {{kStorageScaleKey, bad}});
        try {
            loadLdKtx2(dir / "bad.ktx2");
            ADD_FAILURE() << "'" << bad << "' accepted";
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find("bad.ktx2: iblbake.storageScale"), std::string::npos)
                << e.what();
        }
    }
    fs::remove_all(dir);
}

// Products that fit are stored unscaled (scale 1, written as "1"); rgba32f never needs a scale.
TEST(StorageScale, ProductsThatFitKeepScaleOne) {
    CubeMapChain chain;
    chain.levels.push_back(makeCube(4, rt_test::skyLike));
    for (Ktx2Format format : {Ktx2Format::RGBA16F, Ktx2Format::RGBA32F, Ktx2Format::B10G11R11})
        EXPECT_EQ(chooseProductStorage(chain, format, false).scale, 1.0);
    chain.levels[0].faces[0].at(1, 1) = glm::vec4(65504.0f, 0.0f, 0.0f, 1.0f); // exactly the largest half
    EXPECT_EQ(chooseProductStorage(chain, Ktx2Format::RGBA16F, false).scale, 1.0);
    EXPECT_EQ(chooseProductStorage(chain, Ktx2Format::B10G11R11, false).scale, 0.5);
    chain.levels[0].faces[0].at(1, 1) = glm::vec4(3e38f, std::numeric_limits<float>::infinity(), 0.0f, 1.0f);
    EXPECT_EQ(chooseProductStorage(chain, Ktx2Format::RGBA32F, false).scale, 1.0);
    EXPECT_LE(3e38 * chooseProductStorage(chain, Ktx2Format::RGBA16F, false).scale, 65504.0);
    const Ktx2KeyValues kv = storageKeyValues(ProductStorage{});
    ASSERT_FALSE(kv.empty());
    EXPECT_EQ(kv[0].first, "iblbake.storageScale");
    EXPECT_EQ(kv[0].second, "1");
}

// The clamp is a setting of the stages that store KTX2 products: it enters their cache keys (and only
// theirs), so a bake never reuses a scaled product for a clamped one or the other way round.
TEST(StorageScale, ClampToFormatEntersTheKeysOfTheStoringStages) {
    const fs::path scenes = fs::path(IBLBAKE_SOURCE_DIR) / "data" / "scenes";
    std::ifstream in(scenes / "park.json");
    nlohmann::json scene = nlohmann::json::parse(in);
    scene["outputs"]["irradianceCube"] = true;
    auto keysWith = [&](bool clamp) {
        scene["outputs"]["clampToFormat"] = clamp;
        const Plan plan = planScene(parseScene(scene.dump(), "park.json", scenes));
        std::map<std::string, std::string> hashes;
        for (const PlanStage& stage : plan.stages)
            for (const PlanInput& input : stage.inputs)
                hashes[input.file.string()] = "content";
        return planStageKeys(plan, hashes, "cpu");
    };
    const std::map<std::string, std::string> scaled = keysWith(false), clamped = keysWith(true);
    std::set<std::string> changed;
    for (const auto& [id, key] : scaled)
        if (clamped.at(id) != key) changed.insert(id);
    // The stages that store KTX2 products, and the park's engine outputs made from the specular chain
    // (their keys hold their dependencies').
    EXPECT_EQ(changed,
              (std::set<std::string>{"specular", "irradiance", "probe:pavilion", "gltf", "preview"}));
}

// `iblbake specular` says how it stored the chain: scaled to fit (default), or clamped on request with the
// energy lost per level; the file's key/values agree.
TEST(StorageScale, SpecularCommandReportsTheStorage) {
    const fs::path dir = testDir("cli");
    const std::string common = "specular " + kSampleHdri +
                               " --size 32 --sun-illuminance 100000 --extract-sun " + "--sun-json " +
                               (dir / "sun.json").string() + " -o ";
    const CliRun scaled = runCli(common + (dir / "scaled.ktx2").string());
    ASSERT_EQ(scaled.exitCode, 0) << scaled.err;
    EXPECT_NE(scaled.out.find("storage scaled.ktx2: stored x 2^-"), std::string::npos) << scaled.out;
    EXPECT_NE(scaled.out.find(" 0 clamped texels"), std::string::npos) << scaled.out;
    const Ktx2Image file = readKtx2(dir / "scaled.ktx2");
    EXPECT_LT(ktx2StorageScale(file), 1.0);
    EXPECT_EQ(file.keyValues.at("iblbake.sunInLevel0"), "true");

    const CliRun clamped = runCli(common + (dir / "clamped.ktx2").string() + " --clamp-to-format");
    ASSERT_EQ(clamped.exitCode, 0) << clamped.err;
    EXPECT_NE(
        clamped.out.find("storage clamped.ktx2: clamped to rgba16f on request, energy lost per level: "),
        std::string::npos)
        << clamped.out;
    const Ktx2Image clampedFile = readKtx2(dir / "clamped.ktx2");
    EXPECT_EQ(ktx2StorageScale(clampedFile), 1.0);
    EXPECT_EQ(clampedFile.keyValues.count("iblbake.sunInLevel0"), 0u);
    EXPECT_NE(clampedFile.keyValues.at("iblbake.storageClamped").find("level 0 "), std::string::npos);
    fs::remove_all(dir);
}

} // namespace
