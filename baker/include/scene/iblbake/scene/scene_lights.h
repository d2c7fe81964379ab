// The manifest's products.lights (docs/formats.md "Manifest"): the scene's lights with their geometry and
// both photometric units (Frostbite 4.7.1, Table 12), and their card's file when textured. A function of the
// scene alone, so that the up-to-date check (no engine) can tell a manifest whose lights the scene no
// longer has: they change no stage's key.
#pragma once

#include "iblbake/scene/scene.h"

#include <nlohmann/json.hpp>

namespace ibl {

nlohmann::json sceneLightsJson(const Scene& scene);

} // namespace ibl
