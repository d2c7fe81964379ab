// The work of each stage kind of a scene plan: reads its dependencies' cache entries and the scene's
// files, writes its files into a staging directory (scene_plan.h lists the kinds).
#pragma once

#include "entry_files.h"
#include "iblbake/baker/calibration.h"
#include "iblbake/core/cubemap.h"
#include "iblbake/opencl/executor.h"
#include "iblbake/scene/scene_plan.h"

#include <nlohmann/json.hpp>

#include <filesystem>
#include <functional>
#include <map>
#include <string>

namespace ibl {

struct StageContext {
    const std::string& name; // in front of errors: the scene's name, or the command's
    const PlanStage& stage;
    std::map<std::string, std::filesystem::path> dependencies; // stage id -> its cache entry
    const Executor* executor = nullptr;                        // set when stage.usesBackend
    std::filesystem::path outputDirectory;                     // the staging directory
    // Reports what the stage waits on (ProgressSink::stageWaiting's what, detail and seconds left); may be
    // empty.
    std::function<void(const std::string&, const std::string&, double)> waiting = {};
};

// Throws ibl::Error with a one-line message (naming the scene key path for input problems).
void runStage(const StageContext& context);

// The file in a stage's cache entry that becomes `product` in the output directory.
std::string entryFileFor(const PlanStage& stage, const std::string& product);

// A JSON file of a cache entry; throws ibl::Error naming the file.
nlohmann::json readJsonFile(const std::filesystem::path& file);

// The stages of outputs.gltf and outputs.preview (engine_output_stages.cpp).
void runGltfStage(const StageContext& context);
void runPreviewReferenceStage(const StageContext& context);
void runPreviewStage(const StageContext& context);

// The "calibration" setting of an environment stage ({source, value}, as scene_plan.cpp writes a scene's),
// for a command's plan.
nlohmann::json calibrationChoiceJson(const CalibrationSettings& settings);

// Level 0 of a cube KTX2 of a cache entry; throws ibl::Error naming the file.
CubeMap readCubeFile(const std::filesystem::path& file);

// Writes `doc` as indented JSON; throws ibl::Error naming the file.
void writeJsonFile(const std::filesystem::path& file, const nlohmann::json& doc);

} // namespace ibl
