#include "scene_manifest.h"
#include "iblbake/core/numeric.h"
#include "iblbake/scene/json_vec3.h"

#include "iblbake/bake_state/code_identity.h"
#include "iblbake/baker/irradiance.h"
#include "iblbake/baker/material_preview.h"
#include "iblbake/baker/products.h"
#include "iblbake/baker/specular.h"
#include "iblbake/baker/sun.h"
#include "iblbake/runtime/runtime_light_card.h"
#include "iblbake/scene/scene_lights.h"
#include "scene_stages.h"

#include <glm/geometric.hpp>

#include <cmath>
#include <cstdio>
#include <optional>

namespace ibl {

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

// Columns of R = Rz(z) Ry(y) Rx(x) (x applied first), the volume's axes in world space.
std::array<glm::dvec3, 3> axes(const glm::dvec3& degrees) {
    const glm::dvec3 a = degrees * kDegree;
    const double cx = std::cos(a.x), sx = std::sin(a.x), cy = std::cos(a.y), sy = std::sin(a.y);
    const double cz = std::cos(a.z), sz = std::sin(a.z);
    // Row-major R: [cz cy, cz sy sx - sz cx, cz sy cx + sz sx; sz cy, sz sy sx + cz cx, sz sy cx - cz sx;
    //               -sy, cy sx, cy cx]
    return {glm::dvec3(cz * cy, sz * cy, -sy),
            glm::dvec3(cz * sy * sx - sz * cx, sz * sy * sx + cz * cx, cy * sx),
            glm::dvec3(cz * sy * cx + sz * sx, sz * sy * cx - cz * sx, cy * cx)};
}

json volumeJson(const SceneVolume& v) {
    const bool sphere = v.shape == SceneVolume::Shape::Sphere;
    const std::array<glm::dvec3, 3> r = axes(sphere ? glm::dvec3(0.0) : v.rotationDegrees);
    return {{"shape", sphere ? "sphere" : "box"},
            {"center", vec3Json(v.center)},
            {"extent", sphere ? vec3Json(glm::dvec3(v.radius)) : vec3Json(v.halfExtents)},
            {"axes", {vec3Json(r[0]), vec3Json(r[1]), vec3Json(r[2])}}};
}

std::uint32_t irradianceSamples(const std::string& quality) {
    IrradianceSettings settings;
    settings.quality = parseQuality(quality);
    return irradianceSamplesFor(settings);
}

// A local probe's chain: everything from its plan stage.
LdManifestFacts probeFacts(const PlanStage& stage, const std::string& file) {
    const json& s = stage.settings;
    LdManifestFacts f;
    f.file = file;
    f.format = s.at("ktx2Format").get<std::string>();
    f.faceSize = s.at("faceSize").get<int>();
    f.levels = s.at("levels").get<int>();
    f.integratedLevels = s.at("integratedLevels").get<int>();
    f.mapping = parseMipMapping(s.at("mipMapping").get<std::string>());
    f.validRoughnessMax = s.at("roughnessMax").get<double>();
    f.quality = s.at("quality").get<std::string>();
    return f;
}

// The files of a stage after its first product, each with its hash: a glTF's images, a preview's EXR.
json filesAfterTheFirst(const PlanStage& stage, const std::map<std::string, std::string>& hashes) {
    json files = json::array();
    for (std::size_t i = 1; i < stage.products.size(); ++i)
        files.push_back({{"file", stage.products[i]}, {"contentHash", hashes.at(stage.products[i])}});
    return files;
}

json gltfEntry(const PlanStage& stage, const json& facts, const std::map<std::string, std::string>& hashes) {
    const std::string& file = stage.products.at(0);
    return {
        {"file", file},
        {"format", "glTF 2.0 (JSON), EXT_lights_image_based with RGBD PNG faces beside it" +
                       std::string(facts.at("sun").get<bool>() ? ", the sun as KHR_lights_punctual" : "")},
        {"profile", stage.settings.value("profile", "babylon")}, // the engine profile (cube_profile.h)
        {"levels", facts.at("levels")},
        {"faceSize", facts.at("faceSize")},
        {"intensity", facts.at("intensity")},
        {"contentHash", hashes.at(file)},
        {"files", filesAfterTheFirst(stage, hashes)}};
}

json previewEntry(const PlanStage& stage, const json& facts,
                  const std::map<std::string, std::string>& hashes) {
    const std::string& file = stage.products.at(0);
    return {
        {"file", file},
        {"format", "PNG, 8-bit sRGB: labelled grid; the linear panels (runtime | reference | error) as "
                   "OpenEXR in files"},
        {"width", facts.at("width")},
        {"height", facts.at("height")},
        {"rows", previewRowNames(true)},
        {"roughness", facts.at("roughness")},
        {"error",
         {{"meaning",
           "relative mean luminance error per roughness column, sum |runtime - reference| / sum "
           "reference over the balls' pixels; reference: the converged reference (bright texels "
           "integrated "
           "deterministically, stratified samples for the rest) of the full calibrated environment"},
          {"dielectric", facts.at("error").at("dielectric")},
          {"metal", facts.at("error").at("metal")},
          {"both", facts.at("error").at("both")}}},
        {"referenceErrorEstimate",
         {{"meaning", "the reference's own estimated error per roughness column: sum of its points' error "
                      "estimates (two independent sample halves, its bright-texel grid at half the step) / "
                      "sum reference; how far the error above may be off"},
          {"dielectric", facts.at("referenceErrorEstimate").at("dielectric")},
          {"metal", facts.at("referenceErrorEstimate").at("metal")},
          {"both", facts.at("referenceErrorEstimate").at("both")}}},
        {"contentHash", hashes.at(file)},
        {"files", filesAfterTheFirst(stage, hashes)}};
}

// What a light's card says about the light it was baked for: a warning when its aspect is not the
// rectangle's (the runtime stretches the card over the rectangle).
std::optional<std::string> cardAspectWarning(const SceneLight& l, const fs::path& card) {
    const double aspect = loadLightCard(card).layout.aspect, lightAspect = l.width / l.height;
    if (std::abs(std::log(aspect / lightAspect)) <= 0.01) return std::nullopt;
    char text[256];
    std::snprintf(text, sizeof text,
                  "light '%s': its texture's aspect %.4g differs from the light's %.4g x %.4g (%.4g): the "
                  "card is stretched over the rectangle",
                  l.name.c_str(), aspect, l.width, l.height, lightAspect);
    return std::string(text);
}

} // namespace

json buildManifest(const ManifestInputs& in) {
    const Scene& scene = in.scene;
    std::map<std::string, const PlanStage*> stages;
    for (const PlanStage& s : in.plan.stages)
        stages[s.id] = &s;
    const std::string lightStage = stages.count("sun") ? "sun" : "environment";
    const json calibration = readJsonFile(in.entries.at(lightStage) / kEntryFiles.calibration);
    const CalibrationRecord record = calibrationRecordFromJson(calibration.at("record"));

    json products = json::object();
    if (stages.count("dfg")) {
        const PlanStage& s = *stages["dfg"];
        products["dfg"] = dfgManifestEntry(
            s.settings.at("size").get<std::uint32_t>(), s.settings.at("samples").get<std::uint32_t>(),
            scene.materials.diffuseModel == SceneDiffuseModel::Disney, in.productHashes.at("dfg_lut.ktx2"));
    }
    // How each KTX2 product was stored (its storage scale, or the clamp asked for), from its entry.
    auto addStorage = [&](json& entry, const std::string& stageId) {
        entry.update(productStorageToJson(
            productStorageFromJson(readJsonFile(in.entries.at(stageId) / kEntryFiles.storage))));
    };
    if (stages.count("specular")) {
        products["specular"] = ldManifestEntry(
            ldManifestFactsFromJson(readJsonFile(in.entries.at("specular") / kEntryFiles.ldManifestFacts)),
            in.productHashes.at("specular.ktx2"));
        addStorage(products["specular"], "specular");
        if (products["specular"].contains("roughLayers"))
            products["specular"]["roughLayers"]["contentHash"] = in.productHashes.at(kRoughLayersFile);
    }
    products["diffuse"] = diffuseManifestEntry(readJsonFile(in.entries.at("diffuse") / "diffuse.json"),
                                               in.productHashes.at("diffuse.json"));
    if (stages.count("irradiance")) {
        const json& s = stages["irradiance"]->settings;
        products["irradiance"] = irradianceManifestEntry(
            s.at("faceSize").get<int>(), s.at("ktx2Format").get<std::string>(),
            irradianceSamples(s.at("quality").get<std::string>()), in.productHashes.at("irradiance.ktx2"));
        addStorage(products["irradiance"], "irradiance");
    }
    if (stages.count("sun"))
        products["sun"] = sunManifestEntry(diskLightFromJson(calibration.at("sunLight").dump()),
                                           in.productHashes.at("sun.json"));
    json probes = json::array();
    for (const SceneProbe& p : scene.probes) {
        auto it = stages.find("probe:" + p.name);
        if (it == stages.end()) continue;
        const std::string file = it->second->products.at(0);
        json probe = ldManifestEntry(probeFacts(*it->second, file), in.productHashes.at(file));
        addStorage(probe, it->first);
        addProbeVisibilityToManifest(
            probe, probeVisibilityFactsFromJson(
                       readJsonFile(in.entries.at(it->first) / kEntryFiles.probeVisibilityFacts)));
        probe["name"] = p.name;
        probe["position"] = vec3Json(p.position);
        probe["proxy"] = volumeJson(p.proxy);
        probe["influence"] = volumeJson(p.influence.value_or(p.proxy));
        const std::array<glm::dvec3, 3> r =
            axes(p.proxy.shape == SceneVolume::Shape::Box ? p.proxy.rotationDegrees : glm::dvec3(0.0));
        const glm::dvec3 d = p.position - p.proxy.center;
        probe["captureOffset"] =
            vec3Json(glm::dvec3(glm::dot(d, r[0]), glm::dot(d, r[1]), glm::dot(d, r[2])));
        probe["fadeDistance"] = p.fadeDistance;
        probes.push_back(std::move(probe));
    }
    products["probes"] = probes;
    // Textured lights' cards (light-card stages); the card's KTX2 keys hold its mapping and aspect.
    json lightCards = json::array();
    for (const SceneLight& l : scene.lights) {
        auto it = stages.find("light-card:" + l.name);
        if (it == stages.end()) continue;
        const json& s = it->second->settings;
        const std::string file = it->second->products.at(0);
        lightCards.push_back(
            {{"light", l.name},
             {"file", file},
             {"format", "KTX2 2D array, " + s.at("ktx2Format").get<std::string>() +
                            ": layer 0 the specular chain by footprint radius, layers 1..K the diffuse "
                            "layers by distance (kernels/light_card.h; keys iblbake.card*)"},
             {"size", s.at("size")},
             {"diffuseLayers", s.at("layers")},
             {"normalization", "mean luminance 1 over the light: the light's colour and power scale it"},
             {"contentHash", in.productHashes.at(file)}});
    }
    if (!scene.lights.empty()) { // absent, as other products that were not needed
        products["lights"] = sceneLightsJson(scene);
        products["lightCards"] = lightCards;
    }
    if (stages.count("gltf"))
        products["gltf"] = gltfEntry(
            *stages["gltf"], readJsonFile(in.entries.at("gltf") / kEntryFiles.gltfFacts), in.productHashes);
    if (stages.count("preview"))
        products["preview"] =
            previewEntry(*stages["preview"],
                         readJsonFile(in.entries.at("preview") / kEntryFiles.previewFacts), in.productHashes);

    // What the user should know about the bake, one line each: a sun left in the probe (the check's facts).
    json warnings = json::array();
    if (stages.count("sun-check")) {
        const json check = readJsonFile(in.entries.at("sun-check") / kEntryFiles.sunInProbeFacts);
        if (check.at("detected").get<bool>()) warnings.push_back(check.at("warning"));
    }
    for (const SceneLight& l : scene.lights)
        if (auto it = stages.find("light-card:" + l.name); it != stages.end())
            if (auto w = cardAspectWarning(l, in.entries.at(it->first) / it->second->products.at(0)))
                warnings.push_back(*w);

    json stageKeys = json::array();
    for (const PlanStage& s : in.plan.stages)
        stageKeys.push_back({{"id", s.id}, {"kind", s.kind}, {"key", in.keys.at(s.id)}});
    const SceneMaterials& m = scene.materials;
    json manifest = {
        {"schema", "iblbake.manifest"},
        {"schemaVersion", kManifestSchemaVersion},
        {"generator", "iblbake " IBLBAKE_VERSION},
        {"manifestCode", builtInStageCodeIdentity().at("manifest")}, // read by the up-to-date check
        {"runtimeProfile", scene.outputs.runtimeProfile},
        {"profile", scene.outputs.profile}, // the cubes' iblbake.profile (cube_profile.h)
        {"backend", in.backend},
        {"conventions",
         {{"directions", "right-handed, +Y up"},
          {"cubeFaces", "+X, -X, +Y, -Y, +Z, -Z, OpenGL face orientation"},
          {"roughness", "perceptual roughness r; GGX alpha = r^2"},
          {"sh", "real L2, order (0,0), (1,-1), (1,0), (1,1), (2,-2), (2,-1), (2,0), (2,1), (2,2), standard "
                 "normalization"},
          {"volumes", "axes are the volume's local axes in world space (columns of its rotation); extent is "
                      "the radius (sphere) or half extents (box); captureOffset is along the proxy's axes"}}},
        {"materials",
         {{"roughness", {{"min", m.roughnessMin}, {"max", m.roughnessMax}}},
          {"diffuseModel", m.diffuseModel == SceneDiffuseModel::Disney ? "disney" : "lambert"},
          {"specular", m.specular},
          {"energyCompensation", m.energyCompensation},
          {"specularLookup", m.specularTaps ? "taps" : "single"},
          {"clearCoat", m.clearCoat}}},
        {"products", products},
        {"warnings", warnings},
        {"stages", stageKeys}};
    addCalibrationToManifest(manifest, record, calibration.at("colorSpace").get<std::string>());
    if (calibration.contains("source"))
        addLatLongPixels(manifest, latLongPixelsFromJson(calibration.at("source")));
    return manifest;
}

} // namespace ibl
