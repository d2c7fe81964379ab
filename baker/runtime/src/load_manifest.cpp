#include "iblbake/core/error.h"
#include "iblbake/runtime/runtime_area_lights.h"
#include "iblbake/runtime/runtime_manifest.h"

#include <nlohmann/json.hpp>

#include <fstream>

namespace ibl {

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

glm::vec3 vec3(const json& v) {
    if (!v.is_array() || v.size() != 3) throw Error("needs 3 numbers");
    return glm::vec3(v[0].get<float>(), v[1].get<float>(), v[2].get<float>());
}

ProbeVolume volume(const json& v) {
    const glm::mat3 rotation(vec3(v.at("axes").at(0)), vec3(v.at("axes").at(1)), vec3(v.at("axes").at(2)));
    const std::string shape = v.at("shape").get<std::string>();
    if (shape == "sphere") return sphereVolume(vec3(v.at("center")), vec3(v.at("extent")).x, rotation);
    if (shape == "box") return boxVolume(vec3(v.at("center")), vec3(v.at("extent")), rotation);
    throw Error("shape '" + shape + "' is neither sphere nor box");
}

// Stand-ins when the bake has no specular products: the runtime then runs with specular off.
LdPyramid blackLd() {
    CubeMapChain chain;
    chain.levels.push_back(CubeMap(1));
    for (ImageRGBA& face : chain.levels[0].faces)
        face.pixels.assign(1, glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));
    return ldPyramidFromChain(chain);
}

DfgTable blackDfg() {
    return DfgTable{1, {0.0f, 0.0f, 0.0f}};
}

// products.lights[i]: the light of its geometry and power, its card loaded when it has one.
ManifestLight light(const json& l, const fs::path& dir) {
    ManifestLight out;
    out.name = l.at("name").get<std::string>();
    const std::string shape = l.at("shape").get<std::string>();
    const glm::vec3 position = vec3(l.at("position")), color = vec3(l.at("color"));
    const float lumens = l.at("lumens").get<float>();
    if (!(lumens > 0.0f)) throw Error("light '" + out.name + "': lumens must be positive");
    if (shape == "sphere") {
        out.light = sphereAreaLight(position, l.at("radius").get<float>(), color, lumens);
    } else if (shape == "disk") {
        out.light = diskAreaLight(position, vec3(l.at("normal")), l.at("radius").get<float>(), color, lumens);
    } else if (shape == "rectangle") {
        out.light =
            rectangleAreaLight(position, vec3(l.at("normal")), vec3(l.at("tangent")),
                               l.at("width").get<float>(), l.at("height").get<float>(), color, lumens);
    } else {
        throw Error("light '" + out.name + "': shape '" + shape + "' is not sphere, disk or rectangle");
    }
    if (l.contains("card")) out.card = loadLightCard(dir / l["card"].get<std::string>());
    return out;
}

ManifestProbeSet load(const json& m, const fs::path& dir) {
    if (m.at("schema") != "iblbake.manifest") throw Error("schema: not an iblbake manifest");
    if (m.at("schemaVersion") != 1) throw Error("schemaVersion: only version 1 is known");
    const json& products = m.at("products");
    const json& materials = m.at("materials");
    const bool glossy = products.contains("specular");

    std::array<glm::vec3, 9> sh{};
    const json& coefficients = products.at("diffuse").at("sh").at("irradiance");
    if (coefficients.size() != 9) throw Error("products.diffuse.sh.irradiance: needs 9 coefficients");
    for (std::size_t i = 0; i < 9; ++i)
        sh[i] = vec3(coefficients[i]);

    ManifestProbeSet out{
        ProbeSet(glossy ? loadLdKtx2(dir / products["specular"].at("file").get<std::string>()) : blackLd(),
                 products.contains("dfg") ? loadDfgKtx2(dir / products["dfg"].at("file").get<std::string>())
                                          : blackDfg(),
                 shCoefficientsFrom(sh, false)),
        {},
        m.at("calibration").at("factor").get<double>(),
        m.at("runtimeProfile").get<std::string>(),
        {}};
    if (products.contains("sun")) {
        const json& light = products["sun"].at("light");
        SunDisk sun;
        sun.direction = vec3(light.at("direction"));
        sun.angularRadius = light.at("angularRadius").get<float>();
        sun.color = vec3(light.at("color"));
        sun.illuminance = light.at("illuminance").get<float>();
        out.set.setSun(sun);
    }
    if (glossy && products["specular"].contains("roughLayers")) // docs/formats.md "Rough layers"
        out.set.setRoughLayers(
            loadRoughLayersKtx2(dir / products["specular"]["roughLayers"].at("file").get<std::string>()));
    if (products.contains("irradiance")) // diffuse then reads the cube instead of the SH (runtime.h)
        out.set.setIrradianceCube(
            loadIrradianceKtx2(dir / products["irradiance"].at("file").get<std::string>()));
    for (const json& p : products.at("probes")) {
        LocalProbeDesc desc;
        desc.proxy = volume(p.at("proxy"));
        desc.influence = volume(p.at("influence"));
        desc.captureOffset = vec3(p.at("captureOffset"));
        desc.fadeDistance = p.at("fadeDistance").get<float>();
        const std::string file = p.at("file").get<std::string>();
        LdPyramid ld = loadLdKtx2(dir / file);
        // The visibility itself comes from the file (its key iblbake.visibility); the manifest says which
        // convention it is in, and a probe without "visibility" (every manifest before visibility existed)
        // must have none. A recorded visibility whose stored texels are all 1 (fp16 rounding of a faint one)
        // loads as none, which is what it is.
        if (p.contains("visibility")) {
            const json& v = p["visibility"];
            if (v.at("convention") != kVisibilityPremultipliedAlpha || v.at("channel") != "A")
                throw Error("products.probes: " + file + ": visibility is not premultiplied-alpha in A");
        } else if (!ld.visibility.empty()) {
            throw Error("products.probes: " + file +
                        ": the file has a visibility the manifest does not record");
        }
        out.set.addLocalProbe(desc, std::move(ld));
    }
    for (const json& l : products.value("lights", json::array()))
        out.lights.push_back(light(l, dir));
    out.options.specular = glossy;
    out.options.energyCompensation = materials.at("energyCompensation").get<bool>();
    // Manifests written before the taps existed have no specularLookup: the runtime's default.
    out.options.specularTaps = materials.value("specularLookup", "single") == "taps";
    out.options.diffuseModel =
        materials.at("diffuseModel") == "disney" ? DiffuseModel::Disney : DiffuseModel::Lambert;
    return out;
}

} // namespace

ManifestProbeSet loadProbeSetFromManifest(const fs::path& path) {
    const fs::path file = fs::is_directory(path) ? path / "manifest.json" : path;
    std::ifstream in(file);
    if (!in) throw Error(file.string() + ": cannot read");
    try {
        return load(json::parse(in), file.parent_path());
    } catch (const json::exception& e) {
        throw Error(file.string() + ": " + e.what());
    } catch (const Error& e) {
        throw Error(file.string() + ": " + e.what());
    }
}

} // namespace ibl
