// The planner (scene_plan.h): what a scene's materials and probes need, and nothing else.
#include "iblbake/scene/scene_plan.h"

#include "iblbake/core/format_text.h"
#include "iblbake/core/gltf_names.h"
#include "iblbake/ktx2/cube_profile.h"

#include <cmath>

namespace ibl {

namespace {

using nlohmann::json;

// DFG LUT samples per texel for each quality preset (the CLI's default, 1,024, is production).
unsigned dfgSamples(const std::string& quality) {
    return quality == "draft" ? 256u : quality == "reference" ? 4096u : 1024u;
}

json calibrationJson(const SceneCalibrationChoice& c) {
    json out = {{"source", sceneCalibrationName(c.source)}};
    if (c.source != SceneCalibration::None && c.source != SceneCalibration::Radiometric)
        out["value"] = c.value;
    return out;
}

std::vector<PlanInput> inputsOf(const std::vector<std::filesystem::path>& files, const std::string& keyPath) {
    std::vector<PlanInput> out;
    for (std::size_t i = 0; i < files.size(); ++i)
        out.push_back({files.size() == 1 ? keyPath : keyPath + "[" + std::to_string(i) + "]", files[i]});
    return out;
}

// outputs.mipMapping is one of kMipMappingNames (scene_parse.cpp checks it).
MipMapping sceneMipMapping(const SceneOutputs& o) {
    return mipMappingFromName(o.mipMapping).value_or(MipMapping::Frostbite);
}

// An LD chain's settings. Under an engine profile with its own level rule (three: FilamentLod), the chain
// holds at each level the roughness that engine reads there, down to its smallest face, as `iblbake specular
// --profile three` bakes it (cube_profile.h).
json ldSettings(const SceneOutputs& o, const SceneMaterials& m, int faceSize) {
    const EngineProfile& engine = engineProfile(o.profile);
    const bool engineLevels = engine.levelRule == LevelRule::FilamentLod;
    const int levels = engineLevels ? engineLevelCount(engine, faceSize) : mipLevelCount(faceSize);
    const MipMapping mapping = engineLevels ? MipMapping::FilamentLod : sceneMipMapping(o);
    json settings = {{"faceSize", faceSize},
                     {"levels", levels},
                     {"integratedLevels", lastLevelNeeded(levels, mapping, m.roughnessMax) + 1},
                     {"roughnessMax", m.roughnessMax},
                     {"mipMapping", mipMappingName(mapping)},
                     {"quality", o.quality},
                     {"ktx2Format", o.ktx2Format},
                     {"clampToFormat", o.clampToFormat},
                     {"profile", o.profile}};
    if (engineLevels) settings["levelRule"] = kFilamentLodRuleName;
    return settings;
}

// What the preview's balls are (outputs.preview is set): their size and material model.
json previewBallSettings(const Scene& scene) {
    const SceneMaterials& m = scene.materials;
    return {{"sphereSize", scene.outputs.preview->sphereSize},
            {"diffuseModel", m.diffuseModel == SceneDiffuseModel::Disney ? "disney" : "lambert"},
            {"energyCompensation", m.energyCompensation},
            {"specularLookup", m.specularTaps ? "taps" : "single"}};
}

// outputs.gltf and outputs.preview: made from the products above, after them, only when the scene asks.
void planEngineOutputs(const Scene& scene, bool glossy, const std::string& lightSource, Plan& plan) {
    const SceneOutputs& o = scene.outputs;
    const bool sun = scene.environment.extractSun;
    const bool preview = o.preview && glossy;
    if (preview) {
        // The converged reference of the full calibrated environment (the environment stage's cube, the sun
        // still in it): a stage of its own, so that a bake whose environment and balls are unchanged (new
        // roughness range, new LD settings) does not render it again (issue 46).
        PlanStage reference{"preview-reference",
                            "preview-reference",
                            {"environment"},
                            {},
                            previewBallSettings(scene),
                            {},
                            false,
                            ""};
        reference.settings["targetError"] = kPreviewReferenceTargetError;
        reference.reason = formatText("outputs.preview: the converged reference of the preview's balls, each "
                                      "roughness column until its own estimated error is under %g%%",
                                      100.0 * kPreviewReferenceTargetError);
        plan.stages.push_back(std::move(reference));
    }
    if (!o.gltf) {
        plan.skipped.push_back({"gltf", "gltf-export", "outputs.gltf is not set"});
    } else if (!glossy || o.faceSize < 2) {
        plan.skipped.push_back({"gltf", "gltf-export",
                                !glossy
                                    ? "outputs.gltf: EXT_lights_image_based needs the specular chain, and no "
                                      "material uses specular"
                                    : "outputs.gltf: a 1-texel cube cannot hold roughness 0 and 1"});
    } else {
        // The levels hold what stock Babylon.js reads there (the babylon engine profile), which no mapping
        // bakes: the chain is re-filtered from level 0 (kernels: the backend).
        const int levels = gltfRefilteredLevels(o.faceSize, o.gltf->minFaceSize);
        PlanStage s{"gltf", "gltf-export", {"specular", "diffuse"}, {}, {}, {o.gltf->file}, true, ""};
        if (sun) s.dependsOn.push_back("sun");
        const std::string stem = std::filesystem::path(o.gltf->file).stem().string();
        for (int m = 0; m < levels; ++m)
            for (int f = 0; f < 6; ++f)
                s.products.push_back(gltfSpecularImageName(stem, m, f));
        s.settings = {{"file", o.gltf->file},
                      {"levels", levels},
                      {"profile", "babylon"},
                      {"minFaceSize", o.gltf->minFaceSize},
                      {"quality", o.quality}};
        s.reason =
            "outputs.gltf: glTF 2.0 with EXT_lights_image_based (" + std::to_string(levels) +
            " levels of RGBD PNG faces, re-filtered to the roughness Babylon.js reads, profile babylon)" +
            (sun ? " and the sun as KHR_lights_punctual" : "");
        plan.stages.push_back(std::move(s));
    }

    if (!preview) {
        plan.skipped.push_back({"preview", "material-preview",
                                !o.preview
                                    ? "outputs.preview is not set"
                                    : "outputs.preview: the preview renders through the specular chain, "
                                      "and no material uses specular"});
        return;
    }
    // The runtime's lighting (every distant product it reads) against that reference.
    PlanStage s{"preview", "material-preview", {"preview-reference"}, {}, {}, {}, true, ""};
    for (const PlanStage& p : plan.stages)
        if (p.id == "dfg" || p.id == "specular" || p.id == "diffuse" || p.id == "sun" || p.id == "irradiance")
            s.dependsOn.push_back(p.id);
    const std::filesystem::path file(o.preview->file);
    s.products = {file.string(), std::filesystem::path(file).replace_extension(".exr").string()};
    s.settings = previewBallSettings(scene);
    s.settings["exposure"] = o.preview->exposure;
    s.reason = "outputs.preview: material balls lit by the bake through the runtime beside the brute-force "
               "reference, labelled, with the per-roughness error";
    if (lightSource == "sun") s.reason += " (the sun as the runtime's disk light)";
    plan.stages.push_back(std::move(s));
}

} // namespace

int lastLevelNeeded(int levels, MipMapping mapping, double roughnessMax) {
    for (int m = 0; m < levels - 1; ++m)
        if (double(perceptualRoughnessForLevel(m, levels, mapping)) >= roughnessMax) return m;
    return levels - 1;
}

Plan planScene(const Scene& scene) {
    Plan plan;
    const SceneMaterials& m = scene.materials;
    const SceneOutputs& o = scene.outputs;
    const SceneEnvironment& env = scene.environment;
    const bool glossy = m.specular || m.clearCoat;
    const bool disney = m.diffuseModel == SceneDiffuseModel::Disney;

    if (glossy || disney) {
        PlanStage s{"dfg", "dfg-lut", {}, {}, {}, {"dfg_lut.ktx2"}, true, ""};
        s.settings = {{"size", o.dfgSize}, {"samples", dfgSamples(o.quality)}};
        s.reason = glossy ? "split-sum specular needs DFG1/DFG2 (baked once, shared by every probe)"
                          : "Disney diffuse reads the LUT's third channel";
        plan.stages.push_back(std::move(s));
        if (glossy && !disney)
            plan.notes.push_back("dfg: the Disney channel (B) is not read by Lambert materials");
        if (glossy && m.energyCompensation)
            plan.notes.push_back("dfg: energy compensation reads DFG1 + DFG2 (no extra product)");
    } else {
        plan.skipped.push_back(
            {"dfg", "dfg-lut", "Lambert diffuse-only materials: the SH irradiance needs no LUT"});
    }

    {
        PlanStage s{
            "environment", "environment", {}, inputsOf(env.files, "environment.file"), {}, {}, false, ""};
        s.settings = {{"layout", env.layout},
                      {"colorSpace", env.colorSpace},
                      {"workingColorSpace", env.workingColorSpace},
                      {"rotation", env.rotationDegrees},
                      {"latlongPixels", env.latLongPixels},
                      {"calibration", calibrationJson(env.calibration)},
                      {"faceSize", o.faceSize}};
        s.reason = "ingest and calibrate the distant environment (read by the diffuse" +
                   std::string(glossy ? " and specular" : "") + " stages)";
        plan.stages.push_back(std::move(s));
    }

    std::string lightSource = "environment";
    if (env.extractSun) {
        PlanStage s{"sun", "sun-extract", {"environment"}, {}, {}, {"sun.json"}, false, ""};
        s.settings = json::object();
        if (env.sunMaxSolidAngle) s.settings["sunMaxSolidAngle"] = *env.sunMaxSolidAngle;
        s.reason = "environment.extractSun: the sun becomes an analytic disk light, bakes use the residual";
        plan.stages.push_back(std::move(s));
        plan.skipped.push_back({"sun-check", "sun-in-probe", "environment.extractSun: the sun is extracted"});
        lightSource = "sun";
    } else {
        plan.skipped.push_back({"sun", "sun-extract", "environment.extractSun is false"});
        // A sun left in the probe breaks the split sum: what it costs is measured and reported (a check
        // that finds no sun costs a detection on a 64 px copy; a found one, a few seconds, once per input).
        PlanStage s{"sun-check", "sun-in-probe", {"environment"}, {}, json::object(), {}, true, ""};
        s.reason = "environment.extractSun is false: a detected sun left in the probe is measured on the "
                   "sphere grid and reported as a warning";
        plan.stages.push_back(std::move(s));
    }

    if (glossy) {
        PlanStage s{"specular",
                    "specular-ld",
                    {lightSource},
                    {},
                    ldSettings(o, m, o.faceSize),
                    {"specular.ktx2"},
                    true,
                    ""};
        const int last = s.settings["integratedLevels"].get<int>() - 1;
        const int levels = s.settings["levels"].get<int>();
        s.reason = std::string(m.specular ? "materials use specular" : "clear coat is used") + "; levels 0-" +
                   std::to_string(last) + " of " + std::to_string(levels) + " integrated (roughness max " +
                   json(m.roughnessMax).dump() + ")";
        // The rough layers (docs/formats.md "Rough layers") only when some material reads past r_0; their
        // roughness grid is part of the settings, so a cache entry of another grid is not reused.
        const bool roughLayers = m.roughnessMax > double(roughLayerRoughness(0));
        s.settings["roughLayers"] = roughLayers ? json(roughLayerRoughnessValues()) : json::array();
        if (roughLayers) {
            s.products.push_back(kRoughLayersFile);
            s.reason += "; rough layers for r >= " + json(roughLayerRoughness(0)).dump() + " (" +
                        std::to_string(roughLayerFaceSize(std::uint32_t(o.faceSize))) + "-px faces)";
        }
        // Level 0 (the unconvolved source) keeps the sun's pixels when the format holds them (specular.h
        // keepSunInLevel0): the cube from before the extraction is an input too.
        if (env.extractSun) {
            s.dependsOn.push_back("environment");
            // The detection limit goes into level 0's metadata (iblbake.sunMaxSolidAngle), which the glTF
            // export's re-detection reads.
            if (env.sunMaxSolidAngle) s.settings["sunMaxSolidAngle"] = *env.sunMaxSolidAngle;
            s.reason += "; level 0 keeps the sun's pixels where outputs.ktx2Format holds them";
        }
        plan.stages.push_back(std::move(s));
    } else {
        plan.skipped.push_back({"specular", "specular-ld", "no material uses specular or clear coat"});
    }

    {
        PlanStage s{"diffuse", "diffuse-sh", {lightSource}, {}, {}, {"diffuse.json"}, false, ""};
        s.settings = {{"window", "auto"}};
        s.reason =
            std::string("diffuse lighting: L2 SH irradiance (") + (disney ? "Disney" : "Lambert") + ")";
        plan.stages.push_back(std::move(s));
    }

    // Diffuse is always needed (every material has a diffuse lobe); the cube only when the scene asks.
    if (o.irradianceCube) {
        PlanStage s{"irradiance", "irradiance-cube", {lightSource}, {}, {}, {"irradiance.ktx2"}, true, ""};
        s.settings = {{"method", "sampled"},        {"faceSize", o.irradianceFaceSize},
                      {"quality", o.quality},       {"samples", 0},
                      {"ktx2Format", o.ktx2Format}, {"clampToFormat", o.clampToFormat},
                      {"profile", o.profile}};
        s.reason = "outputs.irradianceCube: diffuse from a cube of E/pi (sampled, bright texels exact)";
        plan.stages.push_back(std::move(s));
    } else {
        plan.skipped.push_back({"irradiance", "irradiance-cube",
                                "outputs.irradianceCube is false: the SH carry the diffuse light"});
    }

    if (scene.probes.empty()) {
        plan.skipped.push_back({"probe:*", "probe-ld", "the scene has no local probes"});
    } else {
        for (std::size_t i = 0; i < scene.probes.size(); ++i) {
            const SceneProbe& p = scene.probes[i];
            const std::string id = "probe:" + p.name;
            if (!glossy) {
                plan.skipped.push_back({id, "probe-ld",
                                        "local probes carry specular only (Frostbite 4.9.3) and no material "
                                        "uses specular"});
                continue;
            }
            const std::string key = "probes[" + std::to_string(i) + "].capture";
            PlanStage s{id,
                        "probe-ld",
                        {},
                        inputsOf(p.capture, key),
                        ldSettings(o, m, o.probeFaceSize),
                        {"probe_" + p.name + ".ktx2"},
                        true,
                        ""};
            for (PlanInput& mask :
                 inputsOf(p.visibilityMask, "probes[" + std::to_string(i) + "].visibilityMask"))
                s.inputs.push_back(std::move(mask));
            s.settings["layout"] = p.layout;
            s.settings["colorSpace"] = p.colorSpace;
            s.settings["workingColorSpace"] = env.workingColorSpace;
            s.settings["rotation"] = p.rotationDegrees;
            s.settings["latlongPixels"] = p.latLongPixels;
            if (p.calibration) {
                s.settings["calibration"] = calibrationJson(*p.calibration);
            } else if (env.calibration.source != SceneCalibration::None) {
                // The same camera and units as the environment: its factor, so its stage is an input.
                s.settings["calibration"] = {{"source", "environment"}};
                s.dependsOn.push_back("environment");
            } else {
                s.settings["calibration"] = calibrationJson(SceneCalibrationChoice{});
            }
            s.reason = "local probe '" + p.name + "': specular LD chain of its capture";
            plan.stages.push_back(std::move(s));
        }
    }
    // Textured lights: one card each (kernels/light_card.h), independent of the environment and the
    // materials (a card serves every roughness). Analytic lights need nothing baked.
    if (scene.lights.empty())
        plan.skipped.push_back({"light-card:*", "light-card", "the scene has no lights"});
    for (std::size_t i = 0; i < scene.lights.size(); ++i) {
        const SceneLight& l = scene.lights[i];
        const std::string id = "light-card:" + l.name;
        if (!l.texture) {
            plan.skipped.push_back({id, "light-card",
                                    "light '" + l.name + "' has no texture: the runtime evaluates its " +
                                        l.shape + " analytically"});
            continue;
        }
        PlanStage s{id,
                    "light-card",
                    {},
                    {{"lights[" + std::to_string(i) + "].texture", *l.texture}},
                    {{"size", l.cardSize},
                     {"layers", l.cardLayers},
                     {"ktx2Format", o.ktx2Format},
                     {"workingColorSpace", env.workingColorSpace}},
                    {"lightcard_" + l.name + ".ktx2"},
                    true,
                    "light '" + l.name + "' is textured: its light card (Drobot 1.3.5)"};
        plan.stages.push_back(std::move(s));
    }
    planEngineOutputs(scene, glossy, lightSource, plan);
    return plan;
}

std::string planText(const Scene& scene, const Plan& plan) {
    std::string text;
    const auto line = [&](const char* pattern, auto... values) { text += formatText(pattern, values...); };
    line("plan    %s -> %s\n", scene.name.c_str(), scene.outputs.directory.string().c_str());
    for (const PlanStage& s : plan.stages) {
        line("run     %-16s %-12s %s\n", s.id.c_str(), s.kind.c_str(), s.reason.c_str());
        line("          settings %s\n", s.settings.dump().c_str());
        for (const PlanInput& in : s.inputs)
            line("          input    %s = %s\n", in.keyPath.c_str(), in.file.string().c_str());
        if (!s.dependsOn.empty()) {
            std::string deps;
            for (const std::string& d : s.dependsOn)
                deps += (deps.empty() ? "" : ", ") + d;
            line("          after    %s\n", deps.c_str());
        }
        for (const std::string& p : s.products)
            line("          product  %s\n", p.c_str());
    }
    for (const SkippedStage& s : plan.skipped)
        line("skip    %-16s %-12s %s\n", s.id.c_str(), s.kind.c_str(), s.reason.c_str());
    for (const std::string& n : plan.notes)
        line("note    %s\n", n.c_str());
    line("last    manifest.json (written after every product)\n");
    return text;
}

json planToJson(const Plan& plan) {
    json stages = json::array(), skipped = json::array();
    for (const PlanStage& s : plan.stages) {
        json inputs = json::array();
        for (const PlanInput& in : s.inputs)
            inputs.push_back({{"key", in.keyPath}, {"file", in.file.string()}});
        stages.push_back({{"id", s.id},
                          {"kind", s.kind},
                          {"dependsOn", s.dependsOn},
                          {"inputs", inputs},
                          {"settings", s.settings},
                          {"products", s.products},
                          {"reason", s.reason}});
    }
    for (const SkippedStage& s : plan.skipped)
        skipped.push_back({{"id", s.id}, {"kind", s.kind}, {"reason", s.reason}});
    return {{"stages", stages}, {"skipped", skipped}, {"notes", plan.notes}};
}

} // namespace ibl
