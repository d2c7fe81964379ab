#include "scene_manifest.h"

#include "iblbake/code_identity.h"
#include "iblbake/irradiance.h"
#include "iblbake/sun.h"
#include "scene_stages.h"

#include <glm/geometric.hpp>

#include <cmath>

namespace ibl {

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

json vec3Json(const glm::dvec3& v) {
    return json::array({v.x, v.y, v.z});
}

// Columns of R = Rz(z) Ry(y) Rx(x) (x applied first), the volume's axes in world space.
std::array<glm::dvec3, 3> axes(const glm::dvec3& degrees) {
    const glm::dvec3 a = degrees * (3.14159265358979323846 / 180.0);
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

json ldProduct(const PlanStage& stage, const std::string& file, const std::string& hash) {
    const json& s = stage.settings;
    const int integrated = s.at("integratedLevels").get<int>();
    return {{"file", file},
            {"format", s.at("ktx2Format")},
            {"faceSize", s.at("faceSize")},
            {"levels", s.at("levels")},
            {"integratedLevels", integrated},
            {"roughnessMapping", s.at("mipMapping")},
            {"roughnessMappingMeaning", s.at("mipMapping") == "linear"
                                            ? "level m of L holds r = m/(L-1)"
                                            : "level m of L holds r = (m/(L-1))^2"},
            {"validRoughnessMax", s.at("roughnessMax")},
            {"quality", s.at("quality")},
            {"contentHash", hash}};
}

} // namespace

json buildManifest(const ManifestInputs& in) {
    const Scene& scene = in.scene;
    std::map<std::string, const PlanStage*> stages;
    for (const PlanStage& s : in.plan.stages)
        stages[s.id] = &s;
    const std::string lightStage = stages.count("sun") ? "sun" : "environment";
    const json calibration = readJsonFile(in.entries.at(lightStage) / kCalibrationFile);

    json products = json::object();
    if (stages.count("dfg")) {
        const PlanStage& s = *stages["dfg"];
        products["dfg"] = {{"file", "dfg_lut.ktx2"},
                           {"format", "rgba32f"},
                           {"size", s.settings.at("size")},
                           {"samples", s.settings.at("samples")},
                           {"layout",
                            "x: NoV = (x+0.5)/N; y: perceptual roughness = (y+0.5)/N, first row first; "
                            "R = DFG1, G = DFG2, B = renormalized Disney diffuse"},
                           {"disneyChannelUsed", scene.materials.diffuseModel == SceneDiffuseModel::Disney},
                           {"contentHash", in.productHashes.at("dfg_lut.ktx2")}};
    }
    if (stages.count("specular")) {
        const PlanStage& stage = *stages["specular"];
        json& specular = products["specular"] =
            ldProduct(stage, "specular.ktx2", in.productHashes.at("specular.ktx2"));
        const fs::path facts = in.entries.at("specular") / kLdFacts;
        specular["sunInLevel0"] = fs::exists(facts) && readJsonFile(facts).at("sunInLevel0").get<bool>();
    }
    {
        const json diffuse = readJsonFile(in.entries.at("diffuse") / "diffuse.json");
        products["diffuse"] = {
            {"file", "diffuse.json"},
            {"sh",
             {{"irradiance", diffuse.at("sh").at("irradiance")},
              {"convention", "L2, DESIGN.md order, pre-scaled: Filament's irradianceSH(n) = "
                             "sum c_i p_i(n) returns the irradiance E(n) (1/pi not folded in)"},
              {"window", diffuse.at("sh").at("window")}}},
            {"contentHash", in.productHashes.at("diffuse.json")}};
    }
    if (stages.count("irradiance")) {
        const json& s = stages["irradiance"]->settings;
        products["irradiance"] = {
            {"file", "irradiance.ktx2"},
            {"faceSize", s.at("faceSize")},
            {"format", s.at("ktx2Format")},
            {"method", "sampled"},
            {"samples", irradianceSamples(s.at("quality").get<std::string>())},
            {"normalization",
             "E/pi: each texel stores the cosine-weighted mean radiance; irradiance E = pi x "
             "value"},
            {"contentHash", in.productHashes.at("irradiance.ktx2")}};
    }
    if (stages.count("sun")) {
        const DiskLight light = diskLightFromJson(calibration.at("sunLight").dump());
        products["sun"] = {
            {"file", "sun.json"},
            {"light",
             {{"direction", vec3Json(light.direction)},
              {"angularRadius", light.angularRadius},
              {"color", vec3Json(light.color)},
              {"illuminance", light.illuminance},
              {"meaning", "disk light toward direction, angular radius in radians, illuminance "
                          "perpendicular to it (lux when calibrated) times color"}}},
            {"contentHash", in.productHashes.at("sun.json")}};
    }
    json probes = json::array();
    for (const SceneProbe& p : scene.probes) {
        auto it = stages.find("probe:" + p.name);
        if (it == stages.end()) continue;
        const std::string file = it->second->products.at(0);
        json probe = ldProduct(*it->second, file, in.productHashes.at(file));
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

    json stageKeys = json::array();
    for (const PlanStage& s : in.plan.stages)
        stageKeys.push_back({{"id", s.id}, {"kind", s.kind}, {"key", in.keys.at(s.id)}});
    const SceneMaterials& m = scene.materials;
    return {
        {"schema", "iblbake.manifest"},
        {"schemaVersion", kManifestSchemaVersion},
        {"generator", "iblbake " IBLBAKE_VERSION},
        {"manifestCode", builtInStageCodeIdentity().at("manifest")}, // read by the up-to-date check
        {"runtimeProfile", scene.outputs.runtimeProfile},
        {"backend", in.backend},
        {"units", calibration.at("units")},
        {"colorSpace", calibration.at("colorSpace")},
        {"calibration", {{"factor", calibration.at("factor")}, {"record", calibration.at("metadata")}}},
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
          {"clearCoat", m.clearCoat}}},
        {"products", products},
        {"stages", stageKeys}};
}

} // namespace ibl
