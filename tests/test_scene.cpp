// Scene files and the planner: values and defaults, one-line errors naming the key path, no crash on any
// prefix of a valid file, and the stage sets of scenes that differ in one need.
#include <iblbake/core/error.h>
#include <iblbake/scene/scene.h>
#include <iblbake/scene/scene_plan.h>

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <set>

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

json minimalScene() {
    return {{"environment", {{"file", "env.hdr"}}}, {"outputs", {{"directory", "out"}}}};
}

ibl::Scene parse(const json& doc) {
    return ibl::parseScene(doc.dump(), "scene.json", "/base");
}

std::string errorOf(const std::string& text) {
    try {
        ibl::parseScene(text, "scene.json", "/base");
    } catch (const ibl::Error& e) {
        return e.what();
    }
    return "(no error)";
}

std::set<std::string> stageIds(const ibl::Plan& plan) {
    std::set<std::string> ids;
    for (const ibl::PlanStage& s : plan.stages)
        ids.insert(s.id);
    return ids;
}

json probe(const std::string& name) {
    return {{"name", name},
            {"capture", name + ".hdr"},
            {"position", {0, 1, 0}},
            {"proxy", {{"shape", "box"}, {"halfExtents", {2, 1, 2}}}}};
}

} // namespace

TEST(SceneParse, ExampleSceneValuesAndResolvedPaths) {
    const fs::path file = fs::path(IBLBAKE_SOURCE_DIR) / "data/scenes/park.json";
    const ibl::Scene s = ibl::loadSceneFile(file);
    EXPECT_EQ(s.environment.files.at(0), (file.parent_path() / "../rooitou_park_1k.hdr").lexically_normal());
    EXPECT_TRUE(fs::exists(s.environment.files.at(0)));
    EXPECT_EQ(s.environment.calibration.source, ibl::SceneCalibration::SunIlluminance);
    EXPECT_EQ(s.environment.calibration.value, 100000.0);
    EXPECT_TRUE(s.environment.extractSun);
    ASSERT_EQ(s.probes.size(), 1u);
    EXPECT_EQ(s.probes[0].proxy.shape, ibl::SceneVolume::Shape::Box);
    EXPECT_EQ(s.probes[0].proxy.halfExtents, glm::dvec3(4, 2, 3));
    EXPECT_TRUE(s.probes[0].influence.has_value());
    EXPECT_EQ(s.materials.diffuseModel, ibl::SceneDiffuseModel::Disney);
    EXPECT_EQ(s.outputs.probeFaceSize, 128);
    EXPECT_EQ(s.outputs.runtimeProfile, "forward+ / mobile-hdr");
}

TEST(SceneParse, SpecularLookupIsTapsOrSingle) {
    json taps = minimalScene();
    taps["materials"] = {{"specularLookup", "taps"}};
    EXPECT_TRUE(parse(taps).materials.specularTaps);
    json wrong = minimalScene();
    wrong["materials"] = {{"specularLookup", "three"}};
    EXPECT_NE(errorOf(wrong.dump()).find("materials.specularLookup"), std::string::npos)
        << errorOf(wrong.dump());
}

TEST(SceneParse, DefaultsOfAMinimalScene) {
    const ibl::Scene s = parse(minimalScene());
    EXPECT_EQ(s.environment.files.at(0), fs::path("/base/env.hdr"));
    EXPECT_EQ(s.environment.calibration.source, ibl::SceneCalibration::None);
    EXPECT_FALSE(s.environment.extractSun);
    EXPECT_TRUE(s.probes.empty());
    EXPECT_TRUE(s.materials.specular);
    EXPECT_FALSE(s.materials.specularTaps);
    EXPECT_EQ(s.materials.diffuseModel, ibl::SceneDiffuseModel::Lambert);
    EXPECT_EQ(s.outputs.directory, fs::path("/base/out"));
    EXPECT_EQ(s.outputs.faceSize, 256);
    EXPECT_EQ(s.outputs.probeFaceSize, 256);
    EXPECT_EQ(s.outputs.quality, "production");
    EXPECT_EQ(s.outputs.ktx2Format, "rgba16f");
    EXPECT_EQ(s.outputs.profile, "standard");
}

TEST(SceneParse, ProxyCentreDefaultsToTheCapturePoint) {
    json doc = minimalScene();
    doc["probes"] = json::array({probe("a")});
    doc["probes"][0]["position"] = {1, 2, 3};
    const ibl::Scene s = parse(doc);
    EXPECT_EQ(s.probes[0].proxy.center, glm::dvec3(1, 2, 3));
    EXPECT_FALSE(s.probes[0].calibration.has_value()); // inherits the environment's factor
}

TEST(SceneParse, ErrorsNameTheKeyPathAndTheProblem) {
    struct Case {
        json doc;
        std::string expected;
    };
    std::vector<Case> cases;
    auto with = [](const std::function<void(json&)>& edit) {
        json d = minimalScene();
        d["probes"] = json::array({probe("a"), probe("b")});
        edit(d);
        return d;
    };
    cases.push_back({with([](json& d) {
                         d["probes"][1]["proxy"]["halfExtents"] = {1, 0, 1};
                     }),
                     "scene.json: probes[1].proxy.halfExtents: must be 3 positive numbers"});
    cases.push_back({with([](json& d) {
                         d["probes"][1]["proxy"]["halfExtents"] = {1, 1};
                     }),
                     "scene.json: probes[1].proxy.halfExtents: must be 3 positive numbers"});
    cases.push_back({with([](json& d) {
                         d["probes"][0]["proxy"] = {{"shape", "sphere"}, {"radius", 0}};
                     }),
                     "scene.json: probes[0].proxy.radius: must be a positive number"});
    cases.push_back(
        {with([](json& d) { d["outptus"] = json::object(); }), "scene.json: outptus: unknown key"});
    cases.push_back({with([](json& d) {
                         d["materials"] = {{"roughness", {{"maxx", 1}}}};
                     }),
                     "scene.json: materials.roughness.maxx: unknown key"});
    cases.push_back({with([](json& d) { d["outputs"]["faceSize"] = "256"; }),
                     "scene.json: outputs.faceSize: must be a number, not a string"});
    cases.push_back({with([](json& d) { d["outputs"]["faceSize"] = 100; }),
                     "scene.json: outputs.faceSize: must be a power of two"});
    cases.push_back({with([](json& d) { d["environment"]["extractSun"] = 1; }),
                     "scene.json: environment.extractSun: must be true or false, not a number"});
    cases.push_back({with([](json& d) { d["environment"]["sunMaxSolidAngle"] = 0.02; }),
                     "scene.json: environment.sunMaxSolidAngle: needs environment.extractSun"});
    cases.push_back({with([](json& d) {
                         d["environment"]["extractSun"] = true;
                         d["environment"]["sunMaxSolidAngle"] = 1;
                     }),
                     "scene.json: environment.sunMaxSolidAngle: must be a number from 1e-06 to 0.5, not 1"});
    cases.push_back({with([](json& d) {
                         d["environment"]["calibration"] = {{"ev100", 12}, {"scale", 2}};
                     }),
                     "scene.json: environment.calibration: give one calibration source"});
    cases.push_back({with([](json& d) { d["probes"][1]["name"] = "a"; }),
                     "scene.json: probes[1].name: 'a' is used by an earlier probe"});
    cases.push_back({with([](json& d) { d.erase("environment"); }), "scene.json: environment: is required"});
    cases.push_back({with([](json& d) { d["probes"][0]["proxy"]["shape"] = "cone"; }),
                     "scene.json: probes[0].proxy.shape: 'cone' is not one of sphere, box"});
    cases.push_back({with([](json& d) {
                         d["materials"] = {{"roughness", {{"min", 0.8}, {"max", 0.2}}}};
                     }),
                     "scene.json: materials.roughness: min must not exceed max"});
    cases.push_back(
        {with([](json& d) { d["probes"] = 3; }), "scene.json: probes: must be an array, not a number"});
    // Text from the file with control bytes (an escaped line break) is quoted: the error stays one line.
    cases.push_back({with([](json& d) { d["probes"][0]["proxy"]["shape"] = "bo\nx"; }),
                     "scene.json: probes[0].proxy.shape: 'bo\\x0Ax' is not one of sphere, box"});
    cases.push_back(
        {with([](json& d) { d["outputs"]["ktx\r2"] = 1; }), "scene.json: outputs.'ktx\\x0D2': unknown key"});
    for (const Case& c : cases) {
        const std::string e = errorOf(c.doc.dump());
        EXPECT_EQ(e.rfind(c.expected, 0), 0u) << "got: " << e;
        EXPECT_EQ(e.find('\n'), std::string::npos) << e;
    }
    EXPECT_EQ(errorOf("{\"environment\": ").rfind("scene.json: not valid JSON", 0), 0u);
    EXPECT_EQ(errorOf("[1, 2]"), "scene.json: must be an object, not an array");
}

// A small fuzz: every prefix, and every single-byte change to a few bytes, of a valid scene either parses or
// throws ibl::Error; nothing else escapes.
TEST(SceneParse, MalformedBytesThrowOnlyIblError) {
    json doc = minimalScene();
    doc["probes"] = json::array({probe("a")});
    doc["materials"] = {{"roughness", {{"min", 0.1}, {"max", 0.5}}}};
    const std::string text = doc.dump();
    auto attempt = [](const std::string& bytes) {
        try {
            ibl::parseScene(bytes, "fuzz", "/");
        } catch (const ibl::Error&) {
        }
    };
    for (std::size_t n = 0; n <= text.size(); ++n)
        EXPECT_NO_THROW(attempt(text.substr(0, n))) << n;
    const char replacements[] = {'\0', '"', '{', ']', '-', '9', 'e', '\xff'};
    for (std::size_t i = 0; i < text.size(); i += 3)
        for (char r : replacements) {
            std::string mutated = text;
            mutated[i] = r;
            EXPECT_NO_THROW(attempt(mutated)) << i;
        }
    EXPECT_NO_THROW(attempt(std::string(100000, '[')));
}

TEST(ScenePlan, StageSetsFollowTheMaterialsAndProbes) {
    json diffuseOnly = minimalScene();
    diffuseOnly["materials"] = {{"specular", false}};
    const std::set<std::string> lambertDiffuse = stageIds(ibl::planScene(parse(diffuseOnly)));
    EXPECT_EQ(lambertDiffuse, (std::set<std::string>{"environment", "sun-check", "diffuse"}));

    json disney = diffuseOnly;
    disney["materials"]["diffuseModel"] = "disney";
    EXPECT_EQ(stageIds(ibl::planScene(parse(disney))),
              (std::set<std::string>{"dfg", "environment", "sun-check", "diffuse"}));

    const std::set<std::string> glossy = stageIds(ibl::planScene(parse(minimalScene())));
    EXPECT_EQ(glossy, (std::set<std::string>{"dfg", "environment", "sun-check", "specular", "diffuse"}));

    json sun = minimalScene();
    sun["environment"]["extractSun"] = true;
    EXPECT_EQ(stageIds(ibl::planScene(parse(sun))),
              (std::set<std::string>{"dfg", "environment", "sun", "specular", "diffuse"}));

    json probes = minimalScene();
    probes["probes"] = json::array({probe("a"), probe("b")});
    const ibl::Plan probePlan = ibl::planScene(parse(probes));
    EXPECT_EQ(stageIds(probePlan), (std::set<std::string>{"dfg", "environment", "sun-check", "specular",
                                                          "diffuse", "probe:a", "probe:b"}));
    // Uncalibrated environment: the probes do not depend on it.
    for (const ibl::PlanStage& s : probePlan.stages)
        if (s.kind == "probe-ld") {
            EXPECT_TRUE(s.dependsOn.empty()) << s.id;
        }

    json probesDiffuseOnly = probes;
    probesDiffuseOnly["materials"] = {{"specular", false}};
    const ibl::Plan skipped = ibl::planScene(parse(probesDiffuseOnly));
    EXPECT_EQ(stageIds(skipped), (std::set<std::string>{"environment", "sun-check", "diffuse"}));
    EXPECT_TRUE(std::any_of(skipped.skipped.begin(), skipped.skipped.end(),
                            [](const ibl::SkippedStage& s) { return s.id == "probe:a"; }));

    json clearCoat = diffuseOnly;
    clearCoat["materials"]["clearCoat"] = true;
    EXPECT_EQ(stageIds(ibl::planScene(parse(clearCoat))),
              (std::set<std::string>{"dfg", "environment", "sun-check", "specular", "diffuse"}));
}

TEST(ScenePlan, CalibratedEnvironmentMakesInheritingProbesDependOnIt) {
    json doc = minimalScene();
    doc["environment"]["calibration"] = {{"ev100", 12}};
    doc["probes"] = json::array({probe("a"), probe("b")});
    doc["probes"][1]["calibration"] = {{"scale", 2}};
    const ibl::Plan plan = ibl::planScene(parse(doc));
    for (const ibl::PlanStage& s : plan.stages) {
        if (s.id == "probe:a") {
            EXPECT_EQ(s.dependsOn, std::vector<std::string>{"environment"});
        }
        if (s.id == "probe:b") {
            EXPECT_TRUE(s.dependsOn.empty());
        }
    }
}

TEST(ScenePlan, LdLevelsStopAtTheRoughestMaterial) {
    EXPECT_EQ(ibl::mipLevelCount(256), 9);
    EXPECT_EQ(ibl::mipLevelCount(1), 1);
    // Frostbite: level m of 9 holds (m/8)^2: 0.5 is first reached at m = 6 (0.5625), 1 only at m = 8.
    EXPECT_EQ(ibl::lastLevelNeeded(9, ibl::MipMapping::Frostbite, 0.5), 6);
    EXPECT_EQ(ibl::lastLevelNeeded(9, ibl::MipMapping::Frostbite, 1.0), 8);
    EXPECT_EQ(ibl::lastLevelNeeded(9, ibl::MipMapping::Frostbite, 0.0), 0);
    EXPECT_EQ(ibl::lastLevelNeeded(9, ibl::MipMapping::Linear, 0.5), 4);
    json doc = minimalScene();
    doc["materials"] = {{"roughness", {{"max", 0.5}}}};
    for (const ibl::PlanStage& s : ibl::planScene(parse(doc)).stages)
        if (s.id == "specular") {
            EXPECT_EQ(s.settings.at("integratedLevels"), 7);
        }
}

// outputs.profile (the cubes' layout for the engine) is one of standard, three, and decides the LD and
// irradiance stages' settings (so their stage keys); outputs.runtimeProfile stays free text.
TEST(SceneParse, ProfileIsStandardOrThreeAndEntersTheCubeStages) {
    json doc = minimalScene();
    doc["outputs"]["profile"] = "three";
    doc["outputs"]["irradianceCube"] = true;
    const ibl::Scene s = parse(doc);
    EXPECT_EQ(s.outputs.profile, "three");
    int cubeStages = 0;
    for (const ibl::PlanStage& stage : ibl::planScene(s).stages) {
        if (stage.kind != "specular-ld" && stage.kind != "irradiance-cube") continue;
        EXPECT_EQ(stage.settings.at("profile"), "three") << stage.id;
        ++cubeStages;
    }
    EXPECT_EQ(cubeStages, 2);
    doc["outputs"]["profile"] = "unity";
    EXPECT_NE(errorOf(doc.dump()).find("outputs.profile"), std::string::npos) << errorOf(doc.dump());
}

// lights[]: a scene without lights plans no light stage; one textured light plans exactly one card stage
// (its texture the input, its card the product); an untextured light plans none; bad keys are one-line
// errors naming the key.
TEST(ScenePlan, TexturedLightsPlanOneCardStageEach) {
    auto cardStages = [](const ibl::Plan& plan) {
        return std::count_if(plan.stages.begin(), plan.stages.end(),
                             [](const ibl::PlanStage& s) { return s.kind == "light-card"; });
    };
    EXPECT_EQ(cardStages(ibl::planScene(parse(minimalScene()))), 0);

    json doc = minimalScene();
    doc["lights"] =
        json::array({{{"name", "window"}, {"texture", "window.png"}, {"cardSize", 64}, {"lumens", 800}}});
    const ibl::Plan one = ibl::planScene(parse(doc));
    ASSERT_EQ(cardStages(one), 1);
    const auto card = std::find_if(one.stages.begin(), one.stages.end(),
                                   [](const ibl::PlanStage& s) { return s.kind == "light-card"; });
    EXPECT_EQ(card->id, "light-card:window");
    ASSERT_EQ(card->inputs.size(), 1u);
    EXPECT_EQ(card->inputs[0].keyPath, "lights[0].texture");
    EXPECT_EQ(card->inputs[0].file, fs::path("/base/window.png"));
    EXPECT_EQ(card->products, std::vector<std::string>{"lightcard_window.ktx2"});
    EXPECT_EQ(card->settings.at("size"), 64);
    EXPECT_EQ(card->settings.at("layers"), 8);
    EXPECT_TRUE(card->usesBackend);
    // The other stages are those of the scene without the light.
    std::set<std::string> without = stageIds(ibl::planScene(parse(minimalScene())));
    without.insert("light-card:window");
    EXPECT_EQ(stageIds(one), without);

    doc["lights"].push_back({{"name", "bulb"}, {"shape", "sphere"}, {"luminance", 1e4}});
    const ibl::Plan analytic = ibl::planScene(parse(doc));
    EXPECT_EQ(cardStages(analytic), 1);
    EXPECT_TRUE(std::any_of(analytic.skipped.begin(), analytic.skipped.end(),
                            [](const ibl::SkippedStage& s) { return s.id == "light-card:bulb"; }));

    struct Case {
        json light;
        std::string expected;
    } cases[] = {
        {{{"name", "w"}, {"texture", "w.png"}, {"cardSize", 100}},
         "scene.json: lights[0].cardSize: must be a power of two"},
        {{{"name", "w"}, {"texture", "w.png"}, {"cardLayers", 1}},
         "scene.json: lights[0].cardLayers: must be a whole number from 2 to 64"},
        {{{"name", "w"}, {"shape", "disk"}, {"texture", "w.png"}},
         "scene.json: lights[0].texture: only a rectangle light can be textured"},
        {{{"name", "w"}, {"shape", "tube"}},
         "scene.json: lights[0].shape: 'tube' is not one of sphere, disk, rectangle"},
        {{{"name", "w"}, {"cardSize", 64}},
         "scene.json: lights[0].cardSize: needs a texture: only textured lights have cards"},
        {{{"name", "w"}, {"textur", "w.png"}}, "scene.json: lights[0].textur: unknown key"},
        {{{"name", "a b"}}, "scene.json: lights[0].name: must be 1 to 64 of A-Z a-z 0-9 _ -"},
        {{{"name", "w"}}, "scene.json: lights[0].lumens: or luminance (cd/m2) is required"},
        {{{"name", "w"}, {"lumens", 10}, {"luminance", 10}},
         "scene.json: lights[0].luminance: and lumens are both given: give one"},
        {{{"name", "w"}, {"lumens", 0}}, "scene.json: lights[0].lumens: must be a positive number"},
        {{{"name", "w"}, {"lumens", 10}, {"shape", "sphere"}, {"normal", {0, 0, 1}}},
         "scene.json: lights[0].normal: a sphere light has none"},
        {{{"name", "w"}, {"lumens", 10}, {"radius", 1}},
         "scene.json: lights[0].radius: a rectangle light has none"},
        {{{"name", "w"}, {"lumens", 10}, {"shape", "disk"}, {"width", 1}},
         "scene.json: lights[0].width: a disk light has none"},
        {{{"name", "w"}, {"lumens", 10}, {"normal", {0, 0, 0}}},
         "scene.json: lights[0].normal: must not be the zero vector"},
        {{{"name", "w"}, {"lumens", 10}, {"normal", {0, 0, 1}}, {"tangent", {0, 0, 2}}},
         "scene.json: lights[0].tangent: must not be parallel to the normal"},
        {{{"name", "w"}, {"lumens", 10}, {"height", -1}},
         "scene.json: lights[0].height: must be a number from 0 to 1e+09, not -1"},
        {{{"name", "w"}, {"lumens", 10}, {"color", {1, -1, 1}}},
         "scene.json: lights[0].color: must be a number from 0 to 1e+06, not -1"},
    };
    for (const Case& c : cases) {
        json bad = minimalScene();
        bad["lights"] = json::array({c.light});
        EXPECT_EQ(errorOf(bad.dump()), c.expected);
    }
    json twice = minimalScene();
    twice["lights"] = json::array({{{"name", "w"}, {"lumens", 1}}, {{"name", "w"}, {"lumens", 1}}});
    EXPECT_EQ(errorOf(twice.dump()), "scene.json: lights[1].name: 'w' is used by an earlier light");
    json notArray = minimalScene();
    notArray["lights"] = json::object();
    EXPECT_EQ(errorOf(notArray.dump()), "scene.json: lights: must be an array, not an object");
}
