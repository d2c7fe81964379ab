// bakeScene (bake_scene.h): keys, cache look-ups, stage runs, then the output directory and the manifest.
#include "iblbake/baker/bake_scene.h"

#include "iblbake/bake_state/content_hash.h"
#include "iblbake/core/error.h"
#include "iblbake/ktx2/atomic_file.h"
#include "iblbake/opencl/executor.h"
#include "scene_manifest.h"
#include "scene_stages.h"
#include "stage_cache.h"
#include "stage_keys.h"

#include <chrono>
#include <map>
#include <optional>
#include <sstream>

namespace ibl {

namespace {

namespace fs = std::filesystem;

double secondsSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

bool needsBackend(const Plan& plan) {
    for (const PlanStage& s : plan.stages)
        if (s.usesBackend) return true;
    return false;
}

// Copies the products into the output directory (a file already holding the same bytes is left alone) and
// returns their hashes.
std::map<std::string, std::string> publishProducts(const Plan& plan,
                                                   const std::map<std::string, fs::path>& entries,
                                                   const fs::path& outputDirectory, BakeSummary& summary) {
    std::map<std::string, std::string> hashes;
    for (const PlanStage& stage : plan.stages)
        for (const std::string& product : stage.products) {
            const fs::path from = entries.at(stage.id) / entryFileFor(stage, product);
            const fs::path to = outputDirectory / product;
            const std::string hash = hashFile(from);
            std::error_code ec;
            bool same = false;
            if (fs::is_regular_file(to, ec)) try {
                    same = hashFile(to) == hash;
                } catch (const Error&) { // unreadable: replace it
                }
            if (!same) copyAtomically(from, to);
            hashes[product] = hash;
            summary.products.push_back(to);
        }
    return hashes;
}

// The stages of a stale bake; `checkedInputHashes` are the check's (empty when it did not read every input).
BakeSummary bakeStages(const Scene& scene, const BakeOptions& options, ProgressSink& progress,
                       const std::map<std::string, std::string>& checkedInputHashes,
                       std::chrono::steady_clock::time_point start) {
    BakeSummary summary;
    const Plan plan = planScene(scene);
    summary.skipped = plan.skipped;
    for (const PlanStage& s : plan.stages)
        summary.stages.push_back({s.id, s.kind, StageStatus::Pending, "", 0.0, s.products});
    std::size_t current = 0;
    try {
        // Every input is read (hashed) before anything is written: a missing file fails the bake here.
        const std::map<std::string, std::string> inputHashes =
            checkedInputHashes.empty() ? hashPlanInputs(scene, plan) : checkedInputHashes;

        std::optional<Executor> executor;
        summary.backend = "none";
        if (needsBackend(plan)) {
            std::ostringstream dropped;
            executor =
                Executor::create(options.backend, options.device,
                                 options.warnings ? *options.warnings : static_cast<std::ostream&>(dropped));
            summary.backend = backendName(executor->backend());
        }

        const std::map<std::string, std::string> keys = planStageKeys(plan, inputHashes, summary.backend);
        for (std::size_t i = 0; i < plan.stages.size(); ++i)
            summary.stages[i].key = keys.at(plan.stages[i].id);

        const fs::path outputDirectory = scene.outputs.directory;
        std::error_code ec;
        fs::create_directories(outputDirectory, ec);
        if (!fs::is_directory(outputDirectory))
            throw OutputError(scene.name + ": outputs.directory: " + outputDirectory.string() +
                              ": cannot create it" + (ec ? ": " + ec.message() : std::string()));
        const StageCache cache(options.cacheDirectory.empty() ? outputDirectory / ".iblbake-cache"
                                                              : options.cacheDirectory);

        std::map<std::string, fs::path> entries;
        const int count = int(plan.stages.size());
        for (current = 0; current < plan.stages.size(); ++current) {
            const PlanStage& stage = plan.stages[current];
            StageResult& result = summary.stages[current];
            progress.stageStart(result, int(current), count);
            const auto stageStart = std::chrono::steady_clock::now();
            std::optional<fs::path> entry;
            if (!options.force) entry = cache.find(result.key);
            if (entry) {
                result.status = StageStatus::Cached;
            } else {
                const fs::path staging = cache.staging(result.key);
                StageContext context{scene, stage, {}, executor ? &*executor : nullptr, staging};
                for (const std::string& dependency : stage.dependsOn)
                    context.dependencies[dependency] = entries.at(dependency);
                try {
                    runStage(context);
                } catch (const OutputError& e) { // a full disk, a read-only directory: the scene in front
                    cache.discard(staging);
                    throw OutputError(scene.name + ": " + e.what());
                } catch (...) {
                    cache.discard(staging);
                    throw;
                }
                entry = cache.commit(result.key, staging);
                result.status = StageStatus::Ran;
            }
            entries[stage.id] = *entry;
            result.seconds = secondsSince(stageStart);
            progress.stageEnd(result, int(current), count);
        }

        // Products first, the manifest last: a bake killed before this point leaves the old manifest, which
        // points only at files that are still there.
        ManifestInputs manifest{scene, plan, entries, keys, {}, summary.backend};
        manifest.productHashes = publishProducts(plan, entries, outputDirectory, summary);
        const fs::path manifestPath = outputDirectory / "manifest.json";
        {
            AtomicFile file(manifestPath);
            const nlohmann::json document = buildManifest(manifest);
            summary.storage = storedProductsFromManifest(document);
            writeFileBytes(file.tempPath(), document.dump(2) + '\n', manifestPath.string());
            file.commit();
        }
        summary.products.push_back(manifestPath);
        summary.manifest = manifestPath;
        summary.ok = true;
        addManifestReport(summary);
    } catch (const std::exception& e) { // ibl::Error, and anything a library throws: one line, no crash
        summary.ok = false;
        summary.error = e.what();
        if (current < summary.stages.size() && summary.stages[current].status == StageStatus::Pending &&
            !summary.stages[current].key.empty())
            summary.stages[current].status = StageStatus::Failed;
    }
    summary.seconds = secondsSince(start);
    progress.done(summary);
    return summary;
}

} // namespace

BakeSummary bakeScene(const Scene& scene, const BakeOptions& options, ProgressSink& progress) {
    const auto start = std::chrono::steady_clock::now();
    const UpToDate checked = checkBakeUpToDate(scene, options); // "--force" when forced: never up to date
    if (checked.upToDate) return reportUpToDateBake(scene, checked, progress, start);
    return bakeStages(scene, options, progress, checked.inputHashes, start);
}

BakeSummary bakeStaleScene(const Scene& scene, const BakeOptions& options, ProgressSink& progress,
                           const UpToDate& checked) {
    return bakeStages(scene, options, progress, checked.inputHashes, std::chrono::steady_clock::now());
}

} // namespace ibl
