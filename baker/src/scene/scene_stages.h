// The work of each stage kind of a scene plan: reads its dependencies' cache entries and the scene's
// files, writes its files into a staging directory (scene_plan.h lists the kinds).
#pragma once

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

// Files every environment-like entry ("environment", "sun") holds: the working-space cube and its
// calibration (JSON: factor, absolute, units, colorSpace, record (products.h calibrationRecordToJson),
// source, sunLight?).
inline constexpr const char* kCubeFile = "cube.ktx2";
inline constexpr const char* kCalibrationFile = "calibration.json";
// Beside the specular stage's chain: its manifest facts (products.h ldManifestFactsToJson, with
// sunInLevel0), so that the manifest needs nothing else from the entry.
inline constexpr const char* kLdManifestFacts = "manifest_facts.json";
// Beside a local probe's chain: whether it carries a visibility and the alpha values its ingest repaired
// (products.h probeVisibilityFactsToJson).
inline constexpr const char* kProbeVisibilityFacts = "visibility_facts.json";
// Beside every KTX2 product of a stage (specular, irradiance, local probe): how it was stored
// (products.h productStorageToJson), for the manifest and the bake summary.
inline constexpr const char* kStorageFile = "storage.json";

// Beside the engine outputs: what the manifest and the bake's report say about them
// (engine_output_stages.cpp). gltf-export: {levels, faceSize, intensity, sun}; material-preview: {width,
// height, roughness, error: {dielectric, metal, both}}.
inline constexpr const char* kGltfFacts = "gltf_facts.json";
inline constexpr const char* kPreviewFacts = "preview_facts.json";
// The preview-reference stage's entry: the balls' reference (material_preview.h writePreviewReference).
inline constexpr const char* kPreviewReferenceFile = "reference.bin";
inline constexpr const char* kPreviewReferenceFacts = "reference_facts.json";

// Beside the sun-in-probe check: {detected, and with a sun: warning, roughness, keptError,
// extractedError} (sun_in_probe.h), which the manifest's warnings read.
inline constexpr const char* kSunInProbeFacts = "sun_in_probe.json";

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
