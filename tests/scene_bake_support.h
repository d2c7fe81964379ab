// A scene bake in one call, for the tests that compare a command's products with a scene's.
#pragma once

#include "scene_test_support.h"

#include <iblbake/baker/bake_scene.h>
#include <iblbake/scene/scene.h>

#include <nlohmann/json.hpp>

#include <filesystem>

namespace ibl::test {

// `scene` written as dir/scene.json and baked on the CPU lanes, quietly (its outputs.directory relative to
// dir).
inline BakeSummary bakeSceneJson(const std::filesystem::path& dir, const nlohmann::json& scene) {
    writeText(dir / "scene.json", scene.dump());
    BakeOptions options;
    options.backend = Backend::Cpu;
    ProgressSink silent;
    return bakeScene(loadSceneFile(dir / "scene.json"), options, silent);
}

} // namespace ibl::test
