// Sun extraction (iblbake/baker/sun.h) and the disk light's JSON form.
#include "iblbake/baker/sun.h"
#include "iblbake/core/error.h"
#include "iblbake/core/numeric.h"

#include <nlohmann/json.hpp>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>

namespace ibl {

DiskLight extractSun(SphereTexels& texels, const SunDetection& detection, const glm::dvec3& weights) {
    if (!detection.found)
        throw Error("sun extraction: no sun was detected" +
                    (detection.reason.empty() ? std::string() : " (" + detection.reason + ")"));
    if (detection.fill.size() != detection.region.size())
        throw Error("sun extraction: internal: region and fill sizes differ");
    if (detection.texelCount != texels.size() ||
        std::any_of(detection.region.begin(), detection.region.end(),
                    [&](std::size_t i) { return i >= texels.size(); }))
        throw Error("sun extraction: the detection belongs to another environment grid");
    std::vector<glm::dvec3> removed(detection.region.size());
    for (std::size_t k = 0; k < detection.region.size(); ++k) {
        const std::size_t i = detection.region[k];
        const glm::vec3 before = texels.rgb(i);
        const glm::vec3 after = glm::min(before, glm::max(detection.fill[k], glm::vec3(0.0f)));
        texels.setRgb(i, after);
        // What was taken out, from the stored float values: the light gets exactly this energy.
        removed[k] = glm::dvec3(before) - glm::dvec3(after);
    }
    return diskLightFromExcess(texels, detection.region, removed, weights);
}

DiskLight extractSun(CubeMap& cube, const SunDetection& detection, const glm::dvec3& weights) {
    SphereTexels texels(cube);
    return extractSun(texels, detection, weights);
}

std::string diskLightToJson(const DiskLight& light, bool calibrated, int indent) {
    nlohmann::ordered_json j;
    j["type"] = "disk";
    j["direction"] = {light.direction.x, light.direction.y, light.direction.z};
    j["elevationDegrees"] = light.elevationDegrees();
    j["azimuthDegrees"] = light.azimuthDegrees();
    j["angularRadiusDegrees"] = light.angularRadiusDegrees();
    j["color"] = {light.color.x, light.color.y, light.color.z};
    j["illuminanceLux"] = light.illuminance;
    j["solidAngleSr"] = light.solidAngle;
    j["units"] = calibrated ? "lux" : "relative";
    return j.dump(indent);
}

DiskLight diskLightFromJson(const std::string& text) {
    nlohmann::json j;
    try {
        j = nlohmann::json::parse(text);
    } catch (const nlohmann::json::exception& e) {
        throw Error(std::string("disk light JSON: ") + e.what());
    }
    auto number = [&](const char* key) {
        if (!j.contains(key) || !j[key].is_number())
            throw Error(std::string("disk light JSON: '") + key + "' is missing or not a number");
        return j[key].get<double>();
    };
    auto vector = [&](const char* key) {
        if (!j.contains(key) || !j[key].is_array() || j[key].size() != 3 ||
            !std::all_of(j[key].begin(), j[key].end(), [](const nlohmann::json& v) { return v.is_number(); }))
            throw Error(std::string("disk light JSON: '") + key + "' is missing or not 3 numbers");
        return glm::dvec3(j[key][0].get<double>(), j[key][1].get<double>(), j[key][2].get<double>());
    };
    if (!j.is_object() || j.value("type", "") != "disk")
        throw Error("disk light JSON: 'type' is not \"disk\"");
    DiskLight light;
    light.direction = vector("direction");
    if (!(glm::length(light.direction) > 0.0)) throw Error("disk light JSON: 'direction' is zero");
    // A direction this program wrote is unit to the last bit, and renormalizing it would move that bit: a
    // light read back from a bake's entry must be the light that was written (product_plans.h: a command's
    // chain records the same sun as before its plan ran through the stage cache).
    if (std::abs(glm::length(light.direction) - 1.0) > 1e-12)
        light.direction = glm::normalize(light.direction);
    light.angularRadius = number("angularRadiusDegrees") * kDegree;
    light.color = vector("color");
    light.illuminance = number("illuminanceLux");
    light.solidAngle = number("solidAngleSr");
    return light;
}

} // namespace ibl
