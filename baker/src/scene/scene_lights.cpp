// products.lights of the manifest (iblbake/scene/scene_lights.h).
#include "iblbake/scene/scene_lights.h"
#include "iblbake/scene/json_vec3.h"

#include <area_lights.h>

namespace ibl {

namespace {

using nlohmann::json;

uint32_t areaShape(const std::string& shape) {
    return shape == "sphere" ? IBL_AREA_SPHERE : shape == "disk" ? IBL_AREA_DISK : IBL_AREA_RECTANGLE;
}

} // namespace

json sceneLightsJson(const Scene& scene) {
    json lights = json::array();
    for (const SceneLight& l : scene.lights) {
        const uint32_t shape = areaShape(l.shape);
        const bool rectangle = shape == IBL_AREA_RECTANGLE;
        const double halfWidth = rectangle ? 0.5 * l.width : l.radius;
        const double halfHeight = rectangle ? 0.5 * l.height : l.radius;
        // Table 12 is linear in the power: its value for 1 lm converts either way.
        const double perLumen = areaLightLuminanceFromPower(shape, float(halfWidth), float(halfHeight), 1.0f);
        const double lumens = l.lumens ? *l.lumens : *l.luminance / perLumen;
        json light = {{"name", l.name},
                      {"shape", l.shape},
                      {"position", vec3Json(l.position)},
                      {"color", vec3Json(l.color)},
                      {"lumens", lumens},
                      {"luminance", l.luminance ? *l.luminance : lumens * perLumen}};
        if (shape != IBL_AREA_SPHERE) light["normal"] = vec3Json(l.normal);
        if (rectangle) {
            light["tangent"] = vec3Json(l.tangent);
            light["width"] = l.width;
            light["height"] = l.height;
        } else {
            light["radius"] = l.radius;
        }
        if (l.texture) light["card"] = "lightcard_" + l.name + ".ktx2";
        lights.push_back(std::move(light));
    }
    return lights;
}

} // namespace ibl
