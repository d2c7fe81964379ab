// `iblbake plan` / `iblbake bake` end to end on small scenes (16-texel faces, draft): bakes run exactly the
// planned stages; re-runs are fully cached; touching one probe's capture re-runs only that probe; bad scenes
// fail with one line naming the key path and leave earlier outputs byte for byte; outputs are deterministic;
// the runtime loads the manifest and shades like the probe set built by hand from the products.
#include "cli_runner.h"
#include "scene_test_support.h"

#include <iblbake/baker/bake_scene.h>
#include <iblbake/baker/material_preview.h>
#include <iblbake/baker/sun.h>
#include <iblbake/ktx2/cube_profile.h>
#include <iblbake/ktx2/ktx2.h>
#include <iblbake/ktx2/storage_scale.h>
#include <iblbake/runtime/runtime_manifest.h>
#include <iblbake/scene/scene.h>
#include <iblbake/scene/scene_plan.h>

#include <gtest/gtest.h>

#include <OpenImageIO/imageio.h>
#include <nlohmann/json.hpp>

#include <iblbake/runtime/runtime_light_card.h>

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

namespace fs = std::filesystem;
using nlohmann::json;
using namespace ibl::test;

namespace {

const std::string kSample = std::string(IBLBAKE_SOURCE_DIR) + "/data/rooitou_park_1k.hdr";

json probeJson(const std::string& name, const std::string& capture, const glm::dvec3& position) {
    return {{"name", name},
            {"capture", capture},
            {"position", {position.x, position.y, position.z}},
            {"proxy", {{"shape", "box"}, {"halfExtents", {2, 1, 1.5}}, {"rotation", {0, 30, 0}}}},
            {"fadeDistance", 0.25}};
}

// A scene directory with env.hdr, a.hdr, b.hdr and a small, fast scene writing to out/.
struct SceneDir {
    fs::path dir;
    json scene;

    explicit SceneDir(const std::string& name) : dir(freshTempDir(name)) {
        writeLatLong(dir / "env.hdr", 0.5f);
        writeLatLong(dir / "a.hdr", 1.0f);
        writeLatLong(dir / "b.hdr", 2.0f);
        scene = {{"environment", {{"file", "env.hdr"}}},
                 {"outputs",
                  {{"directory", "out"},
                   {"quality", "draft"},
                   {"faceSize", 16},
                   {"probeFaceSize", 16},
                   {"dfgSize", 16}}}};
    }
    ~SceneDir() { fs::remove_all(dir); }
    fs::path write(const std::string& file = "scene.json") const {
        writeText(dir / file, scene.dump(2));
        return dir / file;
    }
    fs::path out() const { return dir / "out"; }
};

struct JsonRun {
    CliRun run;
    std::vector<std::string> started; // stage ids in stage-start events
    json summary;                     // the done event's summary
};

JsonRun bakeJson(const fs::path& scene, const std::string& extra = "",
                 const std::string& program = IBLBAKE_CLI) {
    JsonRun r{runProgram(program, "bake " + scene.string() + " --json" + extra), {}, {}};
    std::istringstream lines(r.run.out);
    for (std::string line; std::getline(lines, line);) {
        json event = json::parse(line);
        if (event["event"] == "stage-start") r.started.push_back(event["stage"]);
        if (event["event"] == "done") r.summary = event["summary"];
    }
    return r;
}

std::vector<std::string> plannedIds(const fs::path& scene) {
    CliRun r = runCli("plan " + scene.string() + " --json");
    EXPECT_EQ(r.exitCode, 0) << r.err;
    std::vector<std::string> ids;
    const json plan = json::parse(r.out);
    for (const json& s : plan["stages"])
        ids.push_back(s["id"]);
    return ids;
}

std::map<std::string, std::string> statusById(const json& summary) {
    std::map<std::string, std::string> out;
    for (const json& s : summary["stages"])
        out[s["id"]] = s["status"];
    return out;
}

// A scene file baked through the library on the CPU backend, without progress.
ibl::BakeSummary bakeOnCpu(const fs::path& sceneFile) {
    ibl::BakeOptions options;
    options.backend = ibl::Backend::Cpu;
    ibl::ProgressSink silent;
    return ibl::bakeScene(ibl::loadSceneFile(sceneFile), options, silent);
}

// Every regular file directly in `dir` with its bytes.
std::map<std::string, std::string> snapshot(const fs::path& dir) {
    std::map<std::string, std::string> files;
    for (const fs::directory_entry& e : fs::directory_iterator(dir))
        if (e.is_regular_file()) files[e.path().filename().string()] = readBytes(e.path());
    return files;
}

} // namespace

TEST(SceneBake, RunsExactlyThePlannedStagesForEachNeed) {
    SceneDir d("scene_needs");
    struct Variant {
        std::string name;
        std::function<void(json&)> edit;
        std::set<std::string> expected;
    };
    const std::vector<Variant> variants = {
        {"diffuse-only-lambert",
         [](json& s) {
             s["materials"] = {{"specular", false}};
         },
         {"environment", "sun-check", "diffuse"}},
        {"diffuse-only-disney",
         [](json& s) {
             s["materials"] = {{"specular", false}, {"diffuseModel", "disney"}};
         },
         {"dfg", "environment", "sun-check", "diffuse"}},
        {"glossy", [](json&) {}, {"dfg", "environment", "sun-check", "specular", "diffuse"}},
        {"glossy-probes",
         [](json& s) {
             s["probes"] = json::array({probeJson("a", "a.hdr", {0, 1, 0})});
         },
         {"dfg", "environment", "sun-check", "specular", "diffuse", "probe:a"}},
        {"sun",
         [](json& s) {
             s["environment"]["file"] = kSample;
             s["environment"]["extractSun"] = true;
         },
         {"dfg", "environment", "sun", "specular", "diffuse"}},
    };
    for (const Variant& v : variants) {
        SCOPED_TRACE(v.name);
        json scene = d.scene;
        v.edit(scene);
        scene["outputs"]["directory"] = "out-" + v.name;
        writeText(d.dir / (v.name + ".json"), scene.dump());
        const std::vector<std::string> planned = plannedIds(d.dir / (v.name + ".json"));
        EXPECT_EQ(std::set<std::string>(planned.begin(), planned.end()), v.expected);
        JsonRun r = bakeJson(d.dir / (v.name + ".json"));
        ASSERT_EQ(r.run.exitCode, 0) << r.run.err;
        EXPECT_EQ(r.started, planned);
        EXPECT_EQ(r.summary["ran"], int(planned.size()));
        EXPECT_EQ(r.summary["stages"].size(), planned.size());
        const json manifest = json::parse(readBytes(d.dir / ("out-" + v.name) / "manifest.json"));
        EXPECT_EQ(manifest["products"].contains("specular"), v.expected.count("specular") == 1);
        EXPECT_EQ(manifest["products"].contains("dfg"), v.expected.count("dfg") == 1);
        EXPECT_EQ(manifest["products"].contains("sun"), v.expected.count("sun") == 1);
        EXPECT_EQ(manifest["products"]["probes"].size(), v.expected.count("probe:a"));
        for (const auto& [name, product] : manifest["products"].items())
            if (product.is_object()) {
                EXPECT_TRUE(fs::exists(d.dir / ("out-" + v.name) / product["file"].get<std::string>()))
                    << name;
            }
    }
}

// Rough layers (docs/formats.md "Rough layers") only where a material reads past their first roughness:
// listed with the specular stage's products and in the manifest, and loaded; a scene whose roughest material
// is 0.2 gets none.
TEST(SceneBake, RoughLayersOnlyWhenAMaterialReadsPastTheirFirstRoughness) {
    SceneDir d("scene_rough_layers");
    for (const double roughnessMax : {1.0, 0.2}) {
        SCOPED_TRACE(roughnessMax);
        json scene = d.scene;
        scene["materials"] = {{"roughness", {{"min", 0.0}, {"max", roughnessMax}}}};
        scene["outputs"]["directory"] = "out-" + std::to_string(int(roughnessMax * 10));
        const fs::path file = d.dir / ("rough" + std::to_string(int(roughnessMax * 10)) + ".json");
        writeText(file, scene.dump());
        const ibl::BakeSummary summary = bakeOnCpu(file);
        ASSERT_TRUE(summary.ok) << summary.error;
        const fs::path out = d.dir / scene["outputs"]["directory"].get<std::string>();
        const json specular = json::parse(readBytes(out / "manifest.json"))["products"]["specular"];
        const bool expected = roughnessMax > 0.2025;
        EXPECT_EQ(specular.contains("roughLayers"), expected);
        EXPECT_EQ(fs::exists(out / ibl::kRoughLayersFile), expected);
        EXPECT_EQ(ibl::loadProbeSetFromManifest(out).set.roughLayers().layerCount,
                  expected ? IBL_ROUGH_LAYER_COUNT : 0u);
        if (expected) {
            EXPECT_EQ(specular["roughLayers"]["file"], ibl::kRoughLayersFile);
            EXPECT_EQ(specular["roughLayers"]["layerCount"], IBL_ROUGH_LAYER_COUNT);
            EXPECT_EQ(specular["roughLayers"]["roughness"].front(), 0.2025);
            EXPECT_EQ(specular["roughLayers"]["roughness"].back(), 1.0);
            EXPECT_TRUE(specular["roughLayers"].contains("contentHash"));
            EXPECT_TRUE(specular["roughLayers"].contains("storageScale"));
        }
    }
}

// A detected sun left in the probe (extractSun false): the sun-check stage measures what it costs and the
// manifest, the summary and the report carry the warning; extracting the sun plans no check and warns of
// nothing; a map without a sun runs the check and gets no warning.
TEST(SceneBake, WarnsOfASunLeftInTheProbe) {
    SceneDir d("scene_sun_warning");
    d.scene["environment"]["file"] = kSample;
    d.scene["outputs"]["faceSize"] = 64;
    const std::string wording = "sun detected and left in the probe: runtime error ";
    JsonRun kept = bakeJson(d.write());
    ASSERT_EQ(kept.run.exitCode, 0) << kept.run.err;
    EXPECT_NE(std::find(kept.started.begin(), kept.started.end(), "sun-check"), kept.started.end());
    const json manifest = json::parse(readBytes(d.out() / "manifest.json"));
    ASSERT_EQ(manifest["warnings"].size(), 1u) << manifest.dump();
    EXPECT_EQ(manifest["warnings"][0].get<std::string>().rfind(wording, 0), 0u) << manifest["warnings"];
    EXPECT_EQ(kept.summary["warnings"], manifest["warnings"]);
    const CliRun text = runCli("bake " + (d.dir / "scene.json").string()); // up to date: the same report
    ASSERT_EQ(text.exitCode, 0) << text.err;
    EXPECT_NE(text.out.find("warning     " + wording), std::string::npos) << text.out;

    d.scene["environment"]["extractSun"] = true;
    JsonRun extracted = bakeJson(d.write());
    ASSERT_EQ(extracted.run.exitCode, 0) << extracted.run.err;
    EXPECT_EQ(std::find(extracted.started.begin(), extracted.started.end(), "sun-check"),
              extracted.started.end());
    EXPECT_TRUE(json::parse(readBytes(d.out() / "manifest.json"))["warnings"].empty());

    d.scene["environment"] = {{"file", "env.hdr"}};
    JsonRun noSun = bakeJson(d.write());
    ASSERT_EQ(noSun.run.exitCode, 0) << noSun.run.err;
    EXPECT_NE(std::find(noSun.started.begin(), noSun.started.end(), "sun-check"), noSun.started.end());
    EXPECT_TRUE(noSun.summary["warnings"].empty()) << noSun.summary.dump();
}

// A 512 x 256 lat-long sky with a compact area light: a 10 x 6-pixel softbox of ~8e-3 sr, over the sun
// detector's default 3e-3 sr and under kCompactLightMaxSolidAngle.
void writeSoftboxLatLong(const fs::path& file) {
    const int w = 512, h = 256;
    std::vector<float> pixels(std::size_t(w) * h * 3);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const bool softbox = x >= 240 && x < 250 && y >= 80 && y < 86;
            float* p = &pixels[(std::size_t(y) * w + x) * 3];
            p[0] = softbox ? 400.0f : 0.3f;
            p[1] = softbox ? 380.0f : 0.5f;
            p[2] = softbox ? 300.0f : 0.9f;
        }
    writeRgbFloatImage(file, w, h, pixels);
}

// A compact light left in the probe gets the compact-light warning naming environment.sunMaxSolidAngle;
// extractSun alone finds no sun in it (one line naming the key, nothing written); with the limit the
// softbox is extracted, and level 0's metadata carries the limit (the glTF export's re-detection reads it).
TEST(SceneBake, CompactLightIsExtractedWithItsSolidAngleLimit) {
    SceneDir d("scene_compact_light");
    writeSoftboxLatLong(d.dir / "softbox.exr");
    d.scene["environment"]["file"] = "softbox.exr";
    d.scene["outputs"]["faceSize"] = 64;
    JsonRun kept = bakeJson(d.write());
    ASSERT_EQ(kept.run.exitCode, 0) << kept.run.err;
    ASSERT_EQ(kept.summary["warnings"].size(), 1u) << kept.summary.dump();
    const std::string warning = kept.summary["warnings"][0].get<std::string>();
    EXPECT_EQ(warning.rfind("compact light (disk of ", 0), 0u) << warning;
    EXPECT_NE(warning.find("scene keys environment.extractSun and environment.sunMaxSolidAngle"),
              std::string::npos)
        << warning;
    fs::remove_all(d.out());

    d.scene["environment"]["extractSun"] = true;
    JsonRun noSun = bakeJson(d.write());
    EXPECT_NE(noSun.run.exitCode, 0);
    EXPECT_NE(noSun.run.err.find("environment.extractSun: no sun detected: "), std::string::npos)
        << noSun.run.err;
    EXPECT_FALSE(fs::exists(d.out()));

    d.scene["environment"]["sunMaxSolidAngle"] = 0.02;
    JsonRun extracted = bakeJson(d.write());
    ASSERT_EQ(extracted.run.exitCode, 0) << extracted.run.err;
    EXPECT_TRUE(extracted.summary["warnings"].empty()) << extracted.summary.dump();
    EXPECT_TRUE(fs::exists(d.out() / "sun.json"));
    const ibl::Ktx2Image ld = ibl::readKtx2(d.out() / "specular.ktx2");
    ASSERT_EQ(ld.keyValues.count("iblbake.sunInLevel0"), 1u);
    EXPECT_DOUBLE_EQ(std::stod(ld.keyValues.at("iblbake.sunMaxSolidAngle")), 0.02);
}

TEST(ScenePlanCli, TextPlanGivesEveryStageAndEverySkipWithItsReason) {
    SceneDir d("scene_plan_text");
    d.scene["materials"] = {{"specular", false}};
    d.scene["probes"] = json::array({probeJson("a", "a.hdr", {0, 1, 0})});
    CliRun r = runCli("plan " + d.write().string());
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.out.find("run     environment"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("run     diffuse"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("skip    dfg              dfg-lut      Lambert diffuse-only materials"),
              std::string::npos)
        << r.out;
    EXPECT_NE(r.out.find("skip    specular"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("skip    sun              sun-extract  environment.extractSun is false"),
              std::string::npos)
        << r.out;
    EXPECT_NE(r.out.find("skip    probe:a          probe-ld     local probes carry specular only"),
              std::string::npos)
        << r.out;
    EXPECT_FALSE(fs::exists(d.out())); // planning writes nothing
}

TEST(SceneBake, RerunIsCachedAndTouchingOneCaptureRerunsOnlyItsProbe) {
    SceneDir d("scene_cache");
    d.scene["environment"]["calibration"] = {{"scale", 2.0}};
    d.scene["probes"] = json::array({probeJson("a", "a.hdr", {0, 1, 0}), probeJson("b", "b.hdr", {5, 1, 0})});
    const fs::path scene = d.write();
    JsonRun first = bakeJson(scene);
    ASSERT_EQ(first.run.exitCode, 0) << first.run.err;
    EXPECT_EQ(first.summary["ran"], 7);
    const auto before = snapshot(d.out());

    JsonRun second = bakeJson(scene);
    ASSERT_EQ(second.run.exitCode, 0) << second.run.err;
    EXPECT_EQ(second.summary["ran"], 0);
    EXPECT_EQ(second.summary["cached"], 7);
    EXPECT_EQ(snapshot(d.out()), before);

    writeLatLong(d.dir / "b.hdr", 3.0f);
    JsonRun third = bakeJson(scene);
    ASSERT_EQ(third.run.exitCode, 0) << third.run.err;
    const auto status = statusById(third.summary);
    EXPECT_EQ(status.at("probe:b"), "ran");
    EXPECT_EQ(third.summary["ran"], 1);
    const auto after = snapshot(d.out());
    EXPECT_NE(after.at("probe_b.ktx2"), before.at("probe_b.ktx2"));
    EXPECT_EQ(after.at("probe_a.ktx2"), before.at("probe_a.ktx2"));
    EXPECT_EQ(after.at("specular.ktx2"), before.at("specular.ktx2"));

    JsonRun forced = bakeJson(scene, " --force");
    ASSERT_EQ(forced.run.exitCode, 0) << forced.run.err;
    EXPECT_EQ(forced.summary["ran"], 7);
    EXPECT_EQ(snapshot(d.out()), after); // recomputed, same bytes
}

// The front end (cli/front_end.cpp) answers an unchanged scene without the engine (so without loading
// OpenImageIO or starting OpenCL), and says what the engine would say; anything else needs the engine.
// Scene lights: a textured light's card baked by its light-card stage, listed in the manifest
// (products.lightCards) and the summary's products; products.lights with the geometry and both units
// (Frostbite Table 12), from which the runtime's manifest loader builds the same AreaLights the runtime's
// constructors make (and loads the card); a warning for a card whose aspect is not the rectangle's; a
// rerun up to date, and one after a light's power changed not (all stages cached, the manifest rewritten).
TEST(SceneBake, SceneLightsAreListedLoadedAndKeptUpToDate) {
    SceneDir d("scene_light_card");
    writeLatLong(d.dir / "window.hdr", 1.0f); // 64 x 32: aspect 2
    d.scene["lights"] = json::array({{{"name", "window"},
                                      {"texture", "window.hdr"},
                                      {"cardSize", 16},
                                      {"cardLayers", 2},
                                      {"position", {0, 2, 0}},
                                      {"normal", {0, -1, 0}},
                                      {"tangent", {1, 0, 0}},
                                      {"width", 1.0},
                                      {"height", 0.5},
                                      {"lumens", 800}},
                                     {{"name", "bulb"},
                                      {"shape", "sphere"},
                                      {"position", {1, 1, 1}},
                                      {"radius", 0.1},
                                      {"color", {1, 0.8, 0.6}},
                                      {"luminance", 5e4}}});
    const fs::path scene = d.write();
    JsonRun first = bakeJson(scene);
    ASSERT_EQ(first.run.exitCode, 0) << first.run.err;
    EXPECT_EQ(statusById(first.summary).at("light-card:window"), "ran");
    const json manifest = json::parse(readBytes(d.out() / "manifest.json"));
    const json& cards = manifest["products"]["lightCards"];
    ASSERT_EQ(cards.size(), 1u) << cards;
    EXPECT_EQ(cards[0]["light"], "window");
    EXPECT_EQ(cards[0]["file"], "lightcard_window.ktx2");
    EXPECT_EQ(cards[0]["size"], 16);
    EXPECT_EQ(cards[0]["diffuseLayers"], 2);
    EXPECT_EQ(cards[0]["contentHash"].get<std::string>().size(), 32u);
    const std::vector<std::string> products = first.summary["products"];
    EXPECT_NE(std::find(products.begin(), products.end(), (d.out() / "lightcard_window.ktx2").string()),
              products.end());
    // The card's texture is 2:1, the light 1 x 0.5: no warning.
    EXPECT_TRUE(manifest["warnings"].empty()) << manifest["warnings"];

    const json& lights = manifest["products"]["lights"];
    ASSERT_EQ(lights.size(), 2u);
    EXPECT_EQ(lights[0]["card"], "lightcard_window.ktx2");
    EXPECT_NEAR(lights[0]["luminance"].get<double>(), 800.0 / (3.14159265358979 * 0.5), 1e-3); // phi/(pi A)
    const double r2pi2 = 0.01 * 3.14159265358979 * 3.14159265358979;
    EXPECT_NEAR(lights[1]["lumens"].get<double>(), 5e4 * 4.0 * r2pi2, 1e-2); // L = phi / (4 pi^2 r^2)
    EXPECT_FALSE(lights[1].contains("card"));
    const ibl::ManifestProbeSet loaded = ibl::loadProbeSetFromManifest(d.out());
    ASSERT_EQ(loaded.lights.size(), 2u);
    const ibl::AreaLight window =
        ibl::rectangleAreaLight({0, 2, 0}, {0, -1, 0}, {1, 0, 0}, 1.0f, 0.5f, glm::vec3(1.0f), 800.0f);
    const ibl::AreaLight bulb =
        ibl::sphereAreaLight({1, 1, 1}, 0.1f, {1.0f, 0.8f, 0.6f}, lights[1]["lumens"].get<float>());
    EXPECT_EQ(loaded.lights[0].name, "window");
    ASSERT_TRUE(loaded.lights[0].card.has_value());
    EXPECT_FLOAT_EQ(loaded.lights[0].card->layout.aspect, 2.0f);
    EXPECT_FALSE(loaded.lights[1].card.has_value());
    for (const auto& [got, expected] :
         {std::pair{loaded.lights[0].light, window}, {loaded.lights[1].light, bulb}}) {
        EXPECT_EQ(got.shape, expected.shape);
        EXPECT_EQ(got.position, expected.position);
        EXPECT_EQ(got.normal, expected.normal);
        EXPECT_EQ(got.tangent, expected.tangent);
        EXPECT_FLOAT_EQ(got.halfWidth, expected.halfWidth);
        EXPECT_FLOAT_EQ(got.halfHeight, expected.halfHeight);
        EXPECT_EQ(got.color, expected.color);
        EXPECT_NEAR(got.luminance / expected.luminance, 1.0, 1e-6);
    }
    EXPECT_NEAR(loaded.lights[1].light.luminance, 5e4, 1.0);

    JsonRun second = bakeJson(scene);
    ASSERT_EQ(second.run.exitCode, 0) << second.run.err;
    EXPECT_EQ(second.summary["upToDate"], true) << second.run.out;
    EXPECT_EQ(second.summary["ran"], 0);

    // A square light for the 2:1 card: warned; the power changed: not up to date, nothing re-baked.
    d.scene["lights"][0]["height"] = 1.0;
    d.scene["lights"][0]["lumens"] = 900;
    d.write();
    JsonRun third = bakeJson(scene);
    ASSERT_EQ(third.run.exitCode, 0) << third.run.err;
    EXPECT_EQ(third.summary["upToDate"], false);
    EXPECT_EQ(third.summary["ran"], 0);
    const json rewritten = json::parse(readBytes(d.out() / "manifest.json"));
    EXPECT_EQ(rewritten["products"]["lights"][0]["lumens"], 900.0);
    ASSERT_EQ(rewritten["warnings"].size(), 1u);
    EXPECT_NE(rewritten["warnings"][0].get<std::string>().find("light 'window': its texture's aspect 2"),
              std::string::npos)
        << rewritten["warnings"];
}

TEST(SceneBake, UnchangedRerunIsAnsweredWithoutTheEngineAndAsTheEngineWould) {
    SceneDir d("scene_front_end");
    d.scene["probes"] = json::array({probeJson("a", "a.hdr", {0, 1, 0})});
    const fs::path scene = d.write();
    JsonRun first = bakeJson(scene);
    ASSERT_EQ(first.run.exitCode, 0) << first.run.err;
    EXPECT_EQ(first.summary["upToDate"], false);
    const auto before = snapshot(d.out());
    const fs::path cache = d.out() / ".iblbake-cache", away = d.dir / "cache-away";
    fs::rename(cache, away); // not read when the outputs are up to date

    const std::string withoutEngine =
        "env IBLBAKE_ENGINE=" + (d.dir / "no-engine").string() + " " + IBLBAKE_CLI;
    JsonRun front = bakeJson(scene, "", withoutEngine);
    ASSERT_EQ(front.run.exitCode, 0) << front.run.err;
    EXPECT_EQ(front.summary["upToDate"], true);
    EXPECT_EQ(front.summary["ran"], 0);
    EXPECT_EQ(front.summary["cached"], first.summary["stages"].size());
    EXPECT_EQ(front.started, first.started);
    EXPECT_FALSE(fs::exists(cache));
    fs::rename(away, cache);
    EXPECT_EQ(snapshot(d.out()), before);

    JsonRun engine = bakeJson(scene, "", enginePath()); // bakeScene's own up-to-date answer
    ASSERT_EQ(engine.run.exitCode, 0) << engine.run.err;
    for (JsonRun* r : {&first, &front, &engine})
        for (json& stage : r->summary["stages"])
            stage.erase("seconds");
    for (const char* field : {"seconds", "upToDate", "ran", "cached"}) {
        first.summary.erase(field);
        front.summary.erase(field);
        engine.summary.erase(field);
    }
    for (json& stage : first.summary["stages"])
        stage["status"] = "cached";
    EXPECT_EQ(front.summary, engine.summary);
    EXPECT_EQ(front.summary, first.summary); // same keys, products (manifest last) and backend

    const CliRun text = runProgram(withoutEngine, "bake " + scene.string());
    EXPECT_EQ(text.exitCode, 0) << text.err;
    EXPECT_NE(text.out.find("(0 ran, " + std::to_string(first.started.size()) + " cached, "),
              std::string::npos)
        << text.out;

    // Plans are answered by the front end too, with the engine's very bytes.
    for (const std::string& args : {"plan " + scene.string(), "plan " + scene.string() + " --json"}) {
        const CliRun byFrontEnd = runProgram(withoutEngine, args), byEngine = runProgram(enginePath(), args);
        EXPECT_EQ(byFrontEnd.exitCode, 0) << byFrontEnd.err;
        EXPECT_EQ(byFrontEnd.out, byEngine.out) << args;
        EXPECT_FALSE(byFrontEnd.out.empty());
    }

    // Everything else goes to the engine: --force, a changed input, other commands.
    for (const std::string& args : {"bake " + scene.string() + " --force", std::string("--version")}) {
        const CliRun r = runProgram(withoutEngine, args);
        EXPECT_EQ(r.exitCode, 1) << args;
        EXPECT_EQ(lineCount(r.err), 1) << r.err;
        EXPECT_NE(r.err.find("cannot run the engine " + (d.dir / "no-engine").string()), std::string::npos)
            << r.err;
    }
    writeLatLong(d.dir / "a.hdr", 5.0f);
    EXPECT_EQ(runProgram(withoutEngine, "bake " + scene.string()).exitCode, 1);
    JsonRun changed = bakeJson(scene);
    ASSERT_EQ(changed.run.exitCode, 0) << changed.run.err;
    EXPECT_EQ(changed.summary["ran"], 1);
    EXPECT_EQ(changed.summary["upToDate"], false);
}

TEST(SceneBake, DamagedCacheEntryAndTamperedProductAreRepaired) {
    SceneDir d("scene_damage");
    const fs::path scene = d.write();
    JsonRun first = bakeJson(scene);
    ASSERT_EQ(first.run.exitCode, 0) << first.run.err;
    const auto before = snapshot(d.out());
    std::string specularKey;
    for (const json& s : first.summary["stages"])
        if (s["id"] == "specular") specularKey = s["key"];
    ASSERT_FALSE(specularKey.empty());
    const fs::path entry = d.out() / ".iblbake-cache" / specularKey / "specular.ktx2";
    ASSERT_TRUE(fs::exists(entry));
    std::string bytes = readBytes(entry);
    bytes[bytes.size() / 2] ^= 0x5a;
    writeText(entry, bytes);
    writeText(d.out() / "diffuse.json", "{}");

    JsonRun second = bakeJson(scene);
    ASSERT_EQ(second.run.exitCode, 0) << second.run.err;
    const auto status = statusById(second.summary);
    EXPECT_EQ(status.at("specular"), "ran");
    EXPECT_EQ(status.at("diffuse"), "cached");
    EXPECT_EQ(snapshot(d.out()), before);
}

TEST(SceneBake, BadScenesFailWithOneLineAndLeaveEarlierOutputs) {
    SceneDir d("scene_bad");
    d.scene["probes"] = json::array({probeJson("a", "a.hdr", {0, 1, 0})});
    ASSERT_EQ(runCli("bake " + d.write().string() + " --quiet").exitCode, 0);
    const auto before = snapshot(d.out());
    writeText(d.dir / "not_an_image.hdr", "this is not an image\n");

    struct Bad {
        std::string name;
        std::function<void(json&)> edit;
        std::string expected;
    };
    const std::vector<Bad> bads = {
        {"missing-file", [](json& s) { s["environment"]["file"] = "missing.hdr"; }, "environment.file: "},
        {"wrong-type", [](json& s) { s["outputs"]["faceSize"] = "sixteen"; },
         "outputs.faceSize: must be a number, not a string"},
        {"unknown-key",
         [](json& s) {
             s["materials"] = {{"specualr", false}};
         },
         "materials.specualr: unknown key"},
        {"zero-proxy",
         [](json& s) {
             s["probes"][0]["proxy"]["halfExtents"] = {2, 0, 1};
         },
         "probes[0].proxy.halfExtents: must be 3 positive numbers"},
        {"not-an-image", [](json& s) { s["probes"][0]["capture"] = "not_an_image.hdr"; },
         "probes[0].capture: "},
    };
    for (const Bad& b : bads) {
        SCOPED_TRACE(b.name);
        json scene = d.scene;
        b.edit(scene);
        const fs::path file = d.dir / (b.name + ".json");
        writeText(file, scene.dump());
        CliRun r = runCli("bake " + file.string() + " --quiet");
        EXPECT_NE(r.exitCode, 0);
        EXPECT_EQ(lineCount(r.err), 1) << r.err;
        EXPECT_NE(r.err.find(file.string() + ": " + b.expected), std::string::npos) << r.err;
        EXPECT_EQ(snapshot(d.out()), before);
    }
    CliRun missing = runCli("bake " + (d.dir / "nope.json").string());
    EXPECT_NE(missing.exitCode, 0);
    EXPECT_EQ(lineCount(missing.err), 1) << missing.err;
    EXPECT_EQ(snapshot(d.out()), before);
}

TEST(SceneBake, OutputsAreByteIdenticalAcrossRunsWithSeparateCaches) {
    SceneDir d("scene_determinism");
    d.scene["probes"] = json::array({probeJson("a", "a.hdr", {0, 1, 0})});
    d.scene["materials"] = {{"diffuseModel", "disney"}, {"roughness", {{"max", 0.5}}}};
    const fs::path one = d.write("one.json");
    d.scene["outputs"]["directory"] = "out2";
    const fs::path two = d.write("two.json");
    ASSERT_EQ(runCli("bake " + one.string() + " --quiet").exitCode, 0);
    ASSERT_EQ(runCli("bake " + two.string() + " --quiet").exitCode, 0);
    const auto a = snapshot(d.dir / "out"), b = snapshot(d.dir / "out2");
    // dfg_lut.ktx2, specular.ktx2, specular_rough.ktx2, diffuse.json, probe_a.ktx2, manifest.json
    EXPECT_EQ(a.size(), 6u);
    EXPECT_EQ(a, b);
}

// Two processes baking the same scene at once, sharing the output directory and the cache: both succeed
// and leave what one bake alone leaves.
TEST(SceneBake, ConcurrentBakesOfOneSceneAgree) {
    SceneDir d("scene_concurrent");
    d.scene["probes"] = json::array({probeJson("a", "a.hdr", {0, 1, 0})});
    const fs::path scene = d.write();
    d.scene["outputs"]["directory"] = "alone";
    const fs::path alone = d.write("alone.json");
    ASSERT_EQ(runCli("bake " + alone.string() + " --quiet").exitCode, 0);
    const std::string bake = std::string(IBLBAKE_CLI) + " bake " + scene.string() + " --quiet";
    const std::string both = "(" + bake + " & p=$!; " + bake + "; s=$?; wait $p && exit $s)";
    EXPECT_EQ(std::system(both.c_str()), 0);
    EXPECT_EQ(snapshot(d.out()), snapshot(d.dir / "alone"));
    for (const fs::directory_entry& e : fs::directory_iterator(d.out() / ".iblbake-cache"))
        EXPECT_NE(e.path().filename().string().rfind(".staging-", 0), 0u) << e.path(); // nothing left over
}

TEST(SceneBake, ProgressModes) {
    SceneDir d("scene_progress");
    const fs::path scene = d.write();
    CliRun plain = runCli("bake " + scene.string()); // stderr is a file: one line per stage
    ASSERT_EQ(plain.exitCode, 0) << plain.err;
    int stageLines = 0;
    std::istringstream lines(plain.err);
    for (std::string line; std::getline(lines, line);)
        stageLines += line.rfind("[", 0) == 0;
    EXPECT_EQ(stageLines, 5) << plain.err;
    EXPECT_NE(plain.err.find("[4/5] specular"), std::string::npos) << plain.err;
    EXPECT_NE(plain.out.find("5 ran, 0 cached"), std::string::npos) << plain.out;
    EXPECT_EQ(plain.err.find('\r'), std::string::npos); // no bar redraws when stderr is not a terminal
}

TEST(SceneBake, QuietPrintsNothing) {
    SceneDir d("scene_quiet");
    CliRun quiet = runCli("bake " + d.write().string() + " --quiet");
    ASSERT_EQ(quiet.exitCode, 0);
    EXPECT_TRUE(quiet.out.empty()) << quiet.out;
    EXPECT_TRUE(quiet.err.empty()) << quiet.err;
}

// With the sun extracted, level 0 of the specular chain keeps the sun's pixels when the format holds them
// (keepSunInLevel0, as `iblbake specular --extract-sun`): rgba32f does; rgba16f does too, stored with a
// storage scale (docs/conventions.md "Float storage and the storage scale": a sun calibrated to 100,000 lux
// is ~1e9 cd/m2, half floats end at 65,504), which the manifest records and the loader divides out. Only with
// outputs.clampToFormat (or `bake --clamp-to-format`) does rgba16f keep the residual, and the summary reports
// the energy clamped. Manifest, KTX2 keys and loader agree.
TEST(SceneBake, ExtractedSunStaysInLevel0WhenTheFormatHoldsIt) {
    SceneDir d("scene_sun_level0");
    d.scene["environment"] = {
        {"file", kSample}, {"calibration", {{"sunIlluminance", 100000}}}, {"extractSun", true}};
    d.scene["outputs"]["faceSize"] = 32;
    struct Variant {
        const char* directory;
        const char* format;
        bool clamp;
    };
    for (const Variant& v : {Variant{"out32", "rgba32f", false}, Variant{"out16", "rgba16f", false},
                             Variant{"out16clamp", "rgba16f", true}}) {
        SCOPED_TRACE(v.directory);
        d.scene["outputs"]["directory"] = v.directory;
        d.scene["outputs"]["ktx2Format"] = v.format;
        const JsonRun r = bakeJson(d.write(), v.clamp ? " --clamp-to-format" : "");
        ASSERT_EQ(r.run.exitCode, 0) << r.run.err;
        const fs::path out = d.dir / v.directory;
        const json manifest = json::parse(readBytes(out / "manifest.json"));
        const json& specular = manifest["products"]["specular"];
        EXPECT_EQ(specular["sunInLevel0"], !v.clamp);
        const ibl::Ktx2Image ld = ibl::readKtx2(out / "specular.ktx2");
        EXPECT_EQ(ld.keyValues.count("iblbake.sunInLevel0"), std::size_t(!v.clamp));
        const double scale = ibl::ktx2StorageScale(ld);
        EXPECT_EQ(specular["storageScale"].get<double>(), scale);
        EXPECT_EQ(specular.contains("storageClamp"), v.clamp);
        float stored = 0.0f;
        for (const ibl::ImageRGBA& face : ld.levels[0])
            for (const glm::vec4& t : face.pixels)
                stored = std::max({stored, t.r, t.g, t.b});
        const ibl::LdPyramid loaded = ibl::loadProbeSetFromManifest(out).set.distantLd();
        EXPECT_EQ(loaded.sunInLevel0, !v.clamp);
        const float radiance = *std::max_element(loaded.data.begin(), loaded.data.end());
        if (v.clamp) {
            EXPECT_EQ(scale, 1.0);
            EXPECT_LE(stored, 65504.0f); // the residual, clamped where it exceeds half floats
            const json& reported = r.summary.at("storage").at(0);
            EXPECT_EQ(reported["file"], "specular.ktx2");
            EXPECT_TRUE(reported["clamped"].get<bool>());
            EXPECT_EQ(reported["energyLostPercent"], specular["storageClamp"]["energyLostPercent"]);
            EXPECT_GT(reported["energyLostPercent"][1].get<double>(), 0.0);
        } else {
            if (std::string(v.format) == "rgba16f") {
                EXPECT_LT(scale, 1.0);
                EXPECT_LE(stored, 65504.0f);
            } else {
                EXPECT_EQ(scale, 1.0);
            }
            EXPECT_GT(radiance, 1.0e6f); // the sun's own texels, in radiance
            EXPECT_EQ(r.summary.at("storage").at(0)["storageScale"].get<double>(), scale);
        }
    }
}

// The runtime's manifest loader against a probe set assembled by hand from the same products.
TEST(SceneBake, ManifestLoadsAndShadesLikeTheHandBuiltSet) {
    SceneDir d("scene_manifest");
    d.scene["environment"] = {
        {"file", kSample}, {"calibration", {{"sunIlluminance", 100000}}}, {"extractSun", true}};
    d.scene["probes"] = json::array({probeJson("a", "a.hdr", {0.5, 1, 0.25})});
    d.scene["materials"] = {{"diffuseModel", "disney"}};
    const ibl::BakeSummary summary = bakeOnCpu(d.write());
    ASSERT_TRUE(summary.ok) << summary.error;
    EXPECT_EQ(summary.backend, "cpu");

    const ibl::ManifestProbeSet loaded = ibl::loadProbeSetFromManifest(d.out());
    const json diffuse = json::parse(readBytes(d.out() / "diffuse.json"));
    std::array<glm::vec3, 9> sh{};
    for (std::size_t i = 0; i < 9; ++i) {
        const json& c = diffuse["sh"]["irradiance"][i];
        sh[i] = glm::vec3(c[0].get<float>(), c[1].get<float>(), c[2].get<float>());
    }
    ibl::ProbeSet byHand(ibl::loadLdKtx2(d.out() / "specular.ktx2"),
                         ibl::loadDfgKtx2(d.out() / "dfg_lut.ktx2"), ibl::shCoefficientsFrom(sh, false));
    byHand.setSun(ibl::sunDiskFrom(ibl::diskLightFromJson(readBytes(d.out() / "sun.json"))));
    byHand.setRoughLayers(ibl::loadRoughLayersKtx2(d.out() / ibl::kRoughLayersFile));
    EXPECT_EQ(loaded.set.roughLayers().layerCount, IBL_ROUGH_LAYER_COUNT);
    const glm::dmat3 rotation(glm::rotate(glm::dmat4(1.0), glm::radians(30.0), glm::dvec3(0, 1, 0)));
    ibl::LocalProbeDesc desc;
    desc.proxy =
        ibl::boxVolume(glm::vec3(0.5f, 1.0f, 0.25f), glm::vec3(2.0f, 1.0f, 1.5f), glm::mat3(rotation));
    desc.fadeDistance = 0.25f;
    byHand.addLocalProbe(desc, ibl::loadLdKtx2(d.out() / "probe_a.ktx2"));
    ibl::RuntimeOptions options2;
    options2.diffuseModel = ibl::DiffuseModel::Disney;
    EXPECT_EQ(loaded.options.diffuseModel, ibl::DiffuseModel::Disney);
    EXPECT_TRUE(loaded.options.specular);

    std::vector<ibl::ShadingPoint> points;
    for (int i = 0; i < 64; ++i) {
        const float t = float(i) / 63.0f;
        const glm::vec3 n = glm::normalize(glm::vec3(std::cos(7.0f * t), 0.8f - t, std::sin(7.0f * t)));
        // Inside the probe's box, in its fade band, and outside it.
        points.push_back(ibl::makeShadingPoint(glm::vec3(-3.0f + 6.0f * t, 1.0f, 0.25f), n,
                                               glm::normalize(n + glm::vec3(0.3f, 0.5f, 0.2f)),
                                               glm::vec3(0.7f), float(i % 2), t));
    }
    const std::vector<glm::vec4> a = ibl::evaluateCpu(loaded.set, points, loaded.options);
    const std::vector<glm::vec4> b = ibl::evaluateCpu(byHand, points, options2);
    int local = 0;
    for (std::size_t i = 0; i < points.size(); ++i) {
        for (int c = 0; c < 4; ++c)
            EXPECT_EQ(a[i][c], b[i][c]) << i << " " << c;
        local += b[i].w > 0.0f;
    }
    EXPECT_GT(local, 8);                  // some points are lit by the local probe ...
    EXPECT_LT(local, int(points.size())); // ... and some are not
}

// outputs.profile three: the chain holds at each level the roughness three.js reads there (as `iblbake
// specular --profile three`), and the runtime reads it with the same rule (mip_mapping.h FilamentLod).
TEST(SceneBake, ThreeProfileChainHoldsThreesRoughnessAndTheRuntimeReadsIt) {
    SceneDir d("scene_three");
    d.scene["outputs"]["profile"] = "three";
    d.scene["outputs"]["faceSize"] = 64;
    d.scene["outputs"]["preview"] = {{"sphereSize", 8}};
    const ibl::BakeSummary summary = bakeOnCpu(d.write());
    ASSERT_TRUE(summary.ok) << summary.error;

    const ibl::EngineProfile& three = ibl::engineProfile("three");
    const int levels = ibl::engineLevelCount(three, 64);
    const ibl::Ktx2Image chain = ibl::readKtx2(d.out() / "specular.ktx2");
    ASSERT_EQ(int(chain.levels.size()), levels);
    EXPECT_EQ(chain.keyValues.at("iblbake.roughnessMapping"), "filament-lod");
    EXPECT_EQ(chain.keyValues.at("iblbake.profile"), "three");
    std::istringstream stored(chain.keyValues.at("iblbake.levelRoughness"));
    const std::vector<float> expected = ibl::engineChainRoughness(three, levels, 64);
    for (int m = 0; m < levels; ++m) {
        float r = 0.0f;
        char comma = 0;
        stored >> r;
        if (m + 1 < levels) stored >> comma;
        EXPECT_NEAR(r, expected[std::size_t(m)], 1e-6f) << m;
        // The runtime's lookup reads level m at the roughness level m holds.
        EXPECT_NEAR(
            ibl::mipLevelForRoughness(IBL_MIP_FILAMENT_LOD, expected[std::size_t(m)], std::uint32_t(levels)),
            float(m), 1e-4f)
            << m;
    }
    const json manifest = json::parse(readBytes(d.out() / "manifest.json"));
    EXPECT_EQ(manifest.at("products").at("specular").at("roughnessMapping"), "filament-lod");
    const ibl::ManifestProbeSet loaded = ibl::loadProbeSetFromManifest(d.out());
    EXPECT_EQ(loaded.set.distantLd().mapping, ibl::MipMapping::FilamentLod);
    EXPECT_EQ(loaded.set.distantLd().layout.levelCount, std::uint32_t(levels));
    EXPECT_TRUE(fs::exists(d.out() / "preview.png"));
}

TEST(SceneBake, PreviewAcceptsAManifestBake) {
    SceneDir d("scene_preview");
    ASSERT_EQ(runCli("bake " + d.write().string() + " --quiet").exitCode, 0);
    CliRun r = runCli("preview " + d.out().string() + " --sphere-size 8 --backend cpu -o " +
                      (d.dir / "preview.png").string());
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_TRUE(fs::exists(d.dir / "preview.png"));
}

TEST(SceneBake, IrradianceCubeWhenAskedIsPlannedBakedAndLoaded) {
    SceneDir d("scene_irradiance");
    const auto has = [](const std::vector<std::string>& ids) {
        return std::find(ids.begin(), ids.end(), "irradiance") != ids.end();
    };
    EXPECT_FALSE(has(plannedIds(d.write())));
    d.scene["outputs"]["irradianceCube"] = true;
    d.scene["outputs"]["irradianceFaceSize"] = 8;
    EXPECT_TRUE(has(plannedIds(d.write())));
    d.scene["outputs"]["irradianceFaceSize"] = 12;
    CliRun bad = runCli("plan " + d.write().string());
    EXPECT_NE(bad.exitCode, 0);
    EXPECT_NE(bad.err.find("outputs.irradianceFaceSize: must be a power of two"), std::string::npos)
        << bad.err;
    d.scene["outputs"]["irradianceFaceSize"] = 8;

    const ibl::BakeSummary summary = bakeOnCpu(d.write());
    ASSERT_TRUE(summary.ok) << summary.error;
    const json manifest = json::parse(readBytes(d.out() / "manifest.json"));
    ASSERT_TRUE(manifest["products"].contains("irradiance"));
    EXPECT_EQ(manifest["products"]["irradiance"]["file"], "irradiance.ktx2");
    EXPECT_EQ(manifest["products"]["irradiance"]["faceSize"], 8);
    EXPECT_EQ(ibl::readKtx2(d.out() / "irradiance.ktx2").pixelWidth, 8u);

    const ibl::ManifestProbeSet loaded = ibl::loadProbeSetFromManifest(d.out());
    EXPECT_TRUE(loaded.set.hasIrradianceCube());
    const json diffuse = json::parse(readBytes(d.out() / "diffuse.json"));
    std::array<glm::vec3, 9> sh{};
    for (std::size_t i = 0; i < 9; ++i) {
        const json& c = diffuse["sh"]["irradiance"][i];
        sh[i] = glm::vec3(c[0].get<float>(), c[1].get<float>(), c[2].get<float>());
    }
    const auto handBuilt = [&] {
        ibl::ProbeSet set(ibl::loadLdKtx2(d.out() / "specular.ktx2"),
                          ibl::loadDfgKtx2(d.out() / "dfg_lut.ktx2"), ibl::shCoefficientsFrom(sh, false));
        set.setRoughLayers(ibl::loadRoughLayersKtx2(d.out() / ibl::kRoughLayersFile));
        return set;
    };
    const ibl::ProbeSet shOnly = handBuilt();
    ibl::ProbeSet byHand = handBuilt();
    byHand.setIrradianceCube(ibl::loadIrradianceKtx2(d.out() / "irradiance.ktx2"));
    std::vector<ibl::ShadingPoint> points;
    for (int i = 0; i < 32; ++i) {
        const float t = float(i) / 31.0f;
        const glm::vec3 n = glm::normalize(glm::vec3(std::cos(7.0f * t), 0.8f - t, std::sin(7.0f * t)));
        points.push_back(ibl::makeShadingPoint(glm::vec3(0.0f), n, n, glm::vec3(0.7f), 0.0f, t));
    }
    const std::vector<glm::vec4> a = ibl::evaluateCpu(loaded.set, points, loaded.options);
    const std::vector<glm::vec4> b = ibl::evaluateCpu(byHand, points, ibl::RuntimeOptions{});
    const std::vector<glm::vec4> c = ibl::evaluateCpu(shOnly, points, ibl::RuntimeOptions{});
    int differsFromSh = 0;
    for (std::size_t i = 0; i < points.size(); ++i) {
        for (int k = 0; k < 4; ++k)
            EXPECT_EQ(a[i][k], b[i][k]) << i << " " << k;
        differsFromSh += a[i] != c[i];
    }
    EXPECT_GT(differsFromSh, 0); // the cube, not the SH, lit the loaded set
}

// The status of stage `id` in a bake's summary ("ran", "cached"), or "" when it was not planned.
std::string statusOf(const JsonRun& r, const std::string& id) {
    for (const json& stage : r.summary.value("stages", json::array()))
        if (stage["id"] == id) return stage["status"];
    return "";
}

// The preview's reference is cached by a key of its own (issue 46): a bake with the same environment and
// balls takes it from the cache (a new roughness range re-runs the chain and the preview, not the
// reference), a new environment renders it again; while it renders, the bake says it waits on it.
TEST(SceneBake, PreviewReferenceIsCachedApartFromTheBakeItJudges) {
    SceneDir d("scene_preview_reference");
    d.scene["materials"] = {{"roughness", {{"min", 0.05}, {"max", 0.8}}}};
    d.scene["outputs"]["preview"] = {{"sphereSize", 8}};
    const JsonRun first = bakeJson(d.write());
    ASSERT_EQ(first.run.exitCode, 0) << first.run.err;
    EXPECT_EQ(statusOf(first, "preview-reference"), "ran");
    EXPECT_NE(first.run.out.find(R"("event":"stage-waiting")"), std::string::npos) << first.run.out;
    EXPECT_NE(first.run.out.find(R"("on":"reference")"), std::string::npos) << first.run.out;

    d.scene["materials"]["roughness"]["max"] = 0.6;
    const JsonRun rougher = bakeJson(d.write());
    ASSERT_EQ(rougher.run.exitCode, 0) << rougher.run.err;
    EXPECT_EQ(statusOf(rougher, "preview-reference"), "cached");
    EXPECT_EQ(statusOf(rougher, "specular"), "ran");
    EXPECT_EQ(statusOf(rougher, "preview"), "ran");

    d.scene["environment"]["file"] = "a.hdr";
    const JsonRun otherEnvironment = bakeJson(d.write());
    ASSERT_EQ(otherEnvironment.run.exitCode, 0) << otherEnvironment.run.err;
    EXPECT_EQ(statusOf(otherEnvironment, "preview-reference"), "ran");
}

// outputs.gltf and outputs.preview: planned only when asked, made by the flows of `iblbake gltf` and
// `iblbake preview`, listed in the manifest with every file they write, in the bake's report, and up to
// date on a re-run (answered by the front end, with the same report).
TEST(SceneBake, EngineOutputsOnlyWhenAskedListedAndReported) {
    SceneDir d("scene_engine_outputs");
    const auto has = [](const std::vector<std::string>& ids, const std::string& id) {
        return std::find(ids.begin(), ids.end(), id) != ids.end();
    };
    const std::vector<std::string> without = plannedIds(d.write());
    EXPECT_FALSE(has(without, "gltf"));
    EXPECT_FALSE(has(without, "preview"));
    const json plan = json::parse(runCli("plan " + d.write().string() + " --json").out);
    std::set<std::string> skipped;
    for (const json& s : plan["skipped"])
        skipped.insert(s["id"]);
    EXPECT_TRUE(skipped.count("gltf") && skipped.count("preview")) << plan["skipped"].dump();

    d.scene["environment"] = {
        {"file", kSample}, {"calibration", {{"sunIlluminance", 100000}}}, {"extractSun", true}};
    d.scene["outputs"]["gltf"] = {{"file", "park.gltf"}, {"minFaceSize", 4}};
    d.scene["outputs"]["preview"] = {{"sphereSize", 8}};
    const std::vector<std::string> with = plannedIds(d.write());
    ASSERT_GE(with.size(), 2u);
    EXPECT_EQ(with[with.size() - 2], "gltf");
    EXPECT_EQ(with.back(), "preview");

    const JsonRun r = bakeJson(d.write());
    ASSERT_EQ(r.run.exitCode, 0) << r.run.err;
    const json manifest = json::parse(readBytes(d.out() / "manifest.json"));
    const json& gltf = manifest["products"]["gltf"];
    EXPECT_EQ(gltf["file"], "park.gltf");
    EXPECT_EQ(gltf["levels"], 3); // 16, 8, 4 px: re-filtered to the roughness Babylon reads at each level
    EXPECT_EQ(gltf["profile"], "babylon");
    EXPECT_EQ(gltf["files"].size(), 3u * 6u);
    for (const json& f : gltf["files"])
        EXPECT_TRUE(fs::exists(d.out() / f["file"].get<std::string>())) << f;
    const json& preview = manifest["products"]["preview"];
    EXPECT_EQ(preview["file"], "preview.png");
    EXPECT_EQ(preview["files"][0]["file"], "preview.exr");
    EXPECT_TRUE(fs::exists(d.out() / "preview.exr"));
    const ibl::PreviewLayout layout = ibl::previewLayout(8, true);
    EXPECT_EQ(preview["width"], layout.width);
    EXPECT_EQ(preview["height"], layout.height);
    auto png = OIIO::ImageInput::open((d.out() / "preview.png").string());
    ASSERT_TRUE(png);
    EXPECT_EQ(png->spec().width, layout.width);
    EXPECT_EQ(png->spec().height, layout.height);
    for (const char* row : {"dielectric", "metal", "both"}) {
        ASSERT_EQ(preview["error"][row].size(), std::size_t(ibl::kPreviewColumns)) << row;
        for (const json& e : preview["error"][row])
            EXPECT_TRUE(e.get<double>() >= 0.0 && e.get<double>() < 0.5) << row << " " << e;
    }

    // The same glTF, byte for byte, as `iblbake gltf` exports from the bake directory.
    const fs::path separate = d.dir / "separate";
    fs::create_directories(separate);
    CliRun exported = runCli("gltf " + d.out().string() + " --min-face-size 4 --quality draft -o " +
                             (separate / "park.gltf").string());
    ASSERT_EQ(exported.exitCode, 0) << exported.err;
    EXPECT_EQ(readBytes(separate / "park.gltf"), readBytes(d.out() / "park.gltf"));
    for (const json& f : gltf["files"])
        EXPECT_EQ(readBytes(separate / f["file"].get<std::string>()),
                  readBytes(d.out() / f["file"].get<std::string>()))
            << f;

    // The report: every product, the calibration, the preview's error; the same from an up-to-date re-run.
    std::set<std::string> reported;
    for (const json& p : r.summary["report"])
        reported.insert(p["name"]);
    EXPECT_EQ(reported,
              (std::set<std::string>{"dfg", "specular", "diffuse", "sun", "gltf", "preview", "manifest"}));
    EXPECT_FALSE(r.summary["calibration"].get<std::string>().empty());
    EXPECT_EQ(r.summary["previewError"]["metal"], preview["error"]["metal"]);
    const JsonRun again = bakeJson(d.write());
    ASSERT_EQ(again.run.exitCode, 0) << again.run.err;
    EXPECT_TRUE(again.summary["upToDate"].get<bool>());
    EXPECT_EQ(again.summary["report"], r.summary["report"]);
    EXPECT_EQ(again.summary["previewError"], r.summary["previewError"]);
    CliRun text = runCli("bake " + d.write().string());
    ASSERT_EQ(text.exitCode, 0) << text.err;
    EXPECT_LE(lineCount(text.out), 25) << text.out;
    EXPECT_NE(text.out.find("out/park.gltf"), std::string::npos) << text.out;
    EXPECT_NE(text.out.find("dielectric"), std::string::npos) << text.out;

    d.scene["outputs"]["gltf"] = {{"file", "park.png"}};
    CliRun bad = runCli("plan " + d.write().string());
    EXPECT_NE(bad.exitCode, 0);
    EXPECT_NE(bad.err.find("outputs.gltf.file"), std::string::npos) << bad.err;
}
