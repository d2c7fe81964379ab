// A 3-vector (a direction, a position, a linear RGB colour) as the JSON array [x, y, z] every document
// iblbake writes uses for one.
#pragma once

#include <glm/vec3.hpp>
#include <nlohmann/json.hpp>

namespace ibl {

inline nlohmann::json vec3Json(const glm::dvec3& v) {
    return nlohmann::json::array({v.x, v.y, v.z});
}

// The inverse of vec3Json, exact (the documents' numbers round-trip); throws nlohmann::json's exceptions.
inline glm::dvec3 vec3FromJson(const nlohmann::json& array) {
    return {array.at(0).get<double>(), array.at(1).get<double>(), array.at(2).get<double>()};
}

} // namespace ibl
