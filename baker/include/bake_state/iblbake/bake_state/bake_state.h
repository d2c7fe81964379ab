// What a scene bake reports and what a bake directory holds, without baking (docs/scenes.md "Scenes"):
// options, stage results, the summary and its JSON, progress, and the up-to-date check. No OpenCL,
// OpenImageIO or OpenColorIO: the front end (cli/front_end.cpp) answers up-to-date bakes with this alone; the
// bake itself is baker/bake_scene.h.
#pragma once

#include "iblbake/core/backend.h"
#include "iblbake/core/output_root.h"
#include "iblbake/scene/plan_budget.h"
#include "iblbake/scene/scene.h"
#include "iblbake/scene/scene_plan.h"

#include <chrono>
#include <filesystem>
#include <iosfwd>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace ibl {

struct BakeOptions {
    std::filesystem::path cacheDirectory; // "" = <outputs.directory>/.iblbake-cache
    bool force = false;                   // recompute every stage (and refresh its cache entry)
    Backend backend = Backend::Auto;
    std::string device;               // OpenCL device selector (executor.h)
    std::ostream* warnings = nullptr; // backend warnings (e.g. the CPU fallback); nullptr = dropped
    // Non-empty: the output root (docs/scenes.md "Confined output"): outputs.directory must be written as a
    // relative path and lie below the root once links are resolved, and is reached from the root without
    // following links when the bake writes (iblbake/core/output_root.h). The cache follows it unless
    // cacheDirectory (the operator's) is given.
    std::filesystem::path outputRoot;
    // --max-memory, --max-work (docs/scenes.md "Budget"): a plan whose estimate exceeds either is refused
    // before any input is read past its header.
    BudgetLimits budget;
};

enum class StageStatus { Pending, Ran, Cached, Failed };
const char* stageStatusName(StageStatus status); // "pending", "ran", "cached", "failed"

struct StageResult {
    std::string id, kind;
    StageStatus status = StageStatus::Pending;
    std::string key; // cache key: hash of inputs' content, settings, dependencies' keys, version, backend
    double seconds = 0.0;
    std::vector<std::string> products;
};

// How a KTX2 product was stored (docs/conventions.md "Float storage and the storage scale"), as manifest.json
// records it (products.h productStorageToJson).
struct StoredProduct {
    std::string file;                      // in the output directory
    std::string format;                    // rgba16f, rgba32f, b10g11r11, e5b9g9r9
    double storageScale = 1.0;             // stored RGB = radiance x storageScale
    bool clamped = false;                  // clamped to the format's range on request (outputs.clampToFormat)
    std::vector<double> energyLostPercent; // with clamped: per level
};
// The manifest's products that record a storage scale, in manifest order (specular, irradiance, probes).
std::vector<StoredProduct> storedProductsFromManifest(const nlohmann::json& manifest);
// One line for reports: "<file>: stored x 2^-k (<scale>) to fit <format> (iblbake.storageScale; readers
// divide)", "<file>: fits <format> unscaled", or "<file>: clamped to <format> on request, energy lost per
// level: a% b% ...".
std::string storageLine(const StoredProduct& product);
// One product of a finished bake as its report shows it (read back from manifest.json).
struct ProductReport {
    std::string name;           // the manifest's key: "dfg", "specular", ..., "probe:<name>", "manifest"
    std::filesystem::path path; // its (first) file
    std::uintmax_t bytes = 0;   // all its files together
    int files = 1;              // a glTF's images and a preview's EXR count too
    std::string description;    // what it holds: size, format, levels
};

// The preview's measured error (outputs.preview): relative mean luminance error of the runtime against the
// brute-force reference, per perceptual-roughness column.
struct PreviewErrorReport {
    std::vector<double> roughness, dielectric, metal;
    std::vector<double> referenceError; // the reference's own estimated error, both rows (may be empty)
};

struct BakeSummary {
    bool ok = false;
    std::string error; // one line when !ok
    std::vector<StageResult> stages;
    std::vector<SkippedStage> skipped;
    std::vector<std::filesystem::path> products; // in the output directory, manifest.json last
    std::filesystem::path manifest;
    std::string backend; // "opencl" / "cpu" / "none" (no stage ran kernels)
    double seconds = 0.0;
    bool upToDate = false; // the output directory held this bake already: nothing was read from the cache
    std::vector<StoredProduct> storage; // from the manifest, when ok
    // When ok, from manifest.json: what was made and where, the calibration in one line, the preview's
    // measured error (when the scene asked for a preview).
    std::vector<ProductReport> report;
    std::string calibration;
    std::optional<PreviewErrorReport> previewError;
    std::vector<std::string> warnings; // the manifest's, one line each (a sun left in the probe)
    int ran() const;
    int cached() const;
};

// Receives progress; the default does nothing. Called from the thread that runs bakeScene.
class ProgressSink {
  public:
    virtual ~ProgressSink() = default;
    virtual void stageStart(const StageResult& stage, int index, int count) {}
    virtual void stageEnd(const StageResult& stage, int index, int count) {}
    // A running stage waits on something slow: `what` is "compile" (an OpenCL program built from source,
    // `detail` its file) or "reference" (the preview's converged reference, `detail` its progress), about
    // `secondsLeft` more by the stage's own estimate (negative: no estimate yet).
    virtual void stageWaiting(const StageResult& stage, const std::string& what, const std::string& detail,
                              double secondsLeft) {}
    virtual void done(const BakeSummary& summary) {}
};

// Whether scene.outputs.directory already holds a complete bake of this scene, found without baking: its
// manifest.json parses, lists exactly the plan's stages with the keys the current inputs and settings give
// (under the backend the manifest records, which must be the one options.backend forces unless Auto), and
// every product the plan names holds the bytes of the contentHash the manifest records. Reads the inputs
// and products, never the cache; starts no backend and never throws. A scene `options` refuse before any work
// (refusalBeforeWork) is not up to date, its inputs not hashed.
struct UpToDate {
    bool upToDate = false;
    std::string reason;                          // why not (the first reason found)
    std::vector<std::filesystem::path> products; // when up to date: the products in plan order, manifest last
    std::vector<std::string> keys;               // when up to date: the plan's stage keys, in plan order
    std::string backend;                         // when up to date: the backend the manifest records
    std::vector<StoredProduct> storage;          // when up to date: the manifest's storedProductsFromManifest
    // The content hash of every file the plan reads, by path, when the check got as far as reading them all
    // (empty otherwise): bakeStaleScene takes them instead of reading the inputs again.
    std::map<std::string, std::string> inputHashes;
};
UpToDate checkBakeUpToDate(const Scene& scene, const BakeOptions& options);

// Below an output root (BakeOptions::outputRoot): the scene's outputs.directory relative to the root. Throws
// ibl::OutputError "<scene>: outputs.directory: <directory> is written as an absolute path ..." or "...:
// <directory> is outside the output root <root> ..." before anything is read or written.
std::filesystem::path outputDirectoryBelowRoot(const Scene& scene, const OutputRoot& root);

// Why `options` refuse to bake `scene` (planned as `plan`) before any work, reading no input past its header:
// below an output root, its outputs.directory (outputDirectoryBelowRoot); then its plan over options.budget
// (plan_budget.h budgetRefusal). Nothing when it may be baked. The up-to-date check and the bake both ask, so
// the front end, the engine and batch refuse a scene alike.
std::optional<std::string> refusalBeforeWork(const Scene& scene, const Plan& plan,
                                             const BakeOptions& options);

// The summary of a bake found up to date, as bakeScene reports it: every stage of the plan cached, with its
// key, no time spent in it; `progress` sees each stage start and end, then done. `start` is when the caller
// began (the summary's seconds count from it). bakeScene answers an unchanged scene this way, and so does
// the front end (cli/front_end.cpp) without loading the engine.
BakeSummary reportUpToDateBake(const Scene& scene, const UpToDate& upToDate, ProgressSink& progress,
                               std::chrono::steady_clock::time_point start);

// Fills summary.report, calibration and previewError from summary.manifest (left empty when it cannot be
// read: the report is a courtesy, the bake's outcome is the manifest itself).
void addManifestReport(BakeSummary& summary);

// The summary as JSON: {ok, error, backend, seconds, upToDate, ran, cached, stages: [{id, kind, status, key,
// seconds, products}], skipped: [...], products: [...], manifest, storage: [{file, format, storageScale,
// clamped, energyLostPercent (with clamped)}], report: [{name, path, bytes, files, description}],
// calibration, previewError?: {roughness, dielectric, metal}}.
nlohmann::json bakeSummaryJson(const BakeSummary& summary);

} // namespace ibl
