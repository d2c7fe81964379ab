// bakeScene (bake_scene.h): keys, cache look-ups, stage runs, then the output directory and the manifest.
#include "iblbake/baker/bake_scene.h"

#include "iblbake/bake_state/content_hash.h"
#include "iblbake/core/error.h"
#include "iblbake/core/format_text.h"
#include "iblbake/ktx2/atomic_file.h"
#include "iblbake/ktx2/output_set.h"
#include "iblbake/opencl/executor.h"
#include "scene_manifest.h"
#include "scene_stages.h"
#include "stage_cache.h"
#include "stage_keys.h"
#include "stage_runner.h"

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

// A bake refused before any work: the summary's one line, nothing read past a header, nothing written.
BakeSummary refused(const std::string& error, ProgressSink& progress,
                    std::chrono::steady_clock::time_point start) {
    BakeSummary summary;
    summary.error = error;
    summary.seconds = secondsSince(start);
    progress.done(summary);
    return summary;
}

bool needsBackend(const Plan& plan) {
    for (const PlanStage& s : plan.stages)
        if (s.usesBackend) return true;
    return false;
}

// Every output path of the plan, checked before any work (docs/scenes.md "Failures leave nothing behind"):
// the output directory is a directory or can be made one, and no product or manifest path is a directory.
void checkOutputPaths(const Scene& scene, const Plan& plan) {
    const fs::path& directory = scene.outputs.directory;
    std::error_code ec;
    fs::path existing = directory;
    while (!existing.empty() && !fs::exists(existing, ec) && existing != existing.parent_path())
        existing = existing.parent_path();
    if (existing.empty()) existing = ".";
    if (!fs::is_directory(existing, ec))
        throw OutputError(scene.name + ": outputs.directory: " + directory.string() + ": " +
                          existing.string() + " is not a directory");
    auto mustNotBeADirectory = [&](const std::string& product) {
        if (fs::is_directory(directory / product, ec))
            throw OutputError(scene.name + ": " + (directory / product).string() + ": is a directory");
    };
    for (const PlanStage& stage : plan.stages)
        for (const std::string& product : stage.products)
            mustNotBeADirectory(product);
    mustNotBeADirectory("manifest.json");
}

// Stages the products beside their places in the output directory (a file already holding the same bytes is
// left alone) and returns their hashes; `outputs` moves them into place on commit.
std::map<std::string, std::string> stageProducts(const Plan& plan,
                                                 const std::map<std::string, fs::path>& entries,
                                                 const fs::path& outputDirectory,
                                                 const fs::path& shownDirectory, OutputSet& outputs,
                                                 BakeSummary& summary) {
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
            if (!same)
                outputs.writeFile(to, [&](const fs::path& temporary) { copyProductFile(from, temporary); });
            hashes[product] = hash;
            summary.products.push_back(shownDirectory / product);
        }
    return hashes;
}

// The stages of a stale bake; `checkedInputHashes` are the check's (empty when it did not read every input).
// All or nothing: the stages run into staging directories of the cache, the products and the manifest are
// written beside their places, and only when all of them are written are the cache entries committed and
// the outputs moved into place; a failure anywhere leaves the output tree and the cache as they were (the
// directories it created included).
BakeSummary bakeStages(const Scene& scene, const BakeOptions& options, ProgressSink& progress,
                       const std::map<std::string, std::string>& checkedInputHashes,
                       std::chrono::steady_clock::time_point start) {
    BakeSummary summary;
    const Plan plan = planScene(scene);
    if (std::optional<std::string> refusal = refusalBeforeWork(scene, plan, options))
        return refused(*refusal, progress, start);
    summary.skipped = plan.skipped;
    for (const PlanStage& s : plan.stages)
        summary.stages.push_back({s.id, s.kind, StageStatus::Pending, "", 0.0, s.products});
    std::size_t current = 0;
    // Below an output root the bake writes through the /proc/self/fd path of the directory it opened; its
    // messages show the scene's output directory instead.
    std::string openedDirectory;
    try {
        checkOutputPaths(scene, plan);
        // Every input is read (hashed) before anything is written: a missing file fails the bake here.
        const std::map<std::string, std::string> inputHashes =
            checkedInputHashes.empty() ? hashPlanInputs(scene, plan) : checkedInputHashes;

        std::optional<Executor> executor;
        summary.backend = "none";
        if (needsBackend(plan)) {
            std::ostringstream dropped;
            executor =
                Executor::create(jobBackend(options.backend, options.device), options.device,
                                 options.warnings ? *options.warnings : static_cast<std::ostream&>(dropped));
            summary.backend = backendName(executor->backend());
        }

        const std::map<std::string, std::string> keys = planStageKeys(plan, inputHashes, summary.backend);
        for (std::size_t i = 0; i < plan.stages.size(); ++i)
            summary.stages[i].key = keys.at(plan.stages[i].id);

        // Declared first, destroyed last: the staged entries are gone before it removes the directories it
        // made.
        std::optional<OutputRoot> root;
        OutputSet outputs;
        // Where the bake writes: the scene's directory, or below an output root the path that names the
        // directory opened from the root without following links (reported as the scene's directory).
        fs::path outputDirectory = scene.outputs.directory;
        if (!options.outputRoot.empty()) {
            root.emplace(options.outputRoot);
            outputDirectory = outputs.createDirectoriesBelow(*root, outputDirectoryBelowRoot(scene, *root),
                                                             scene.name + ": outputs.directory");
            openedDirectory = outputDirectory.string();
        }
        const fs::path cacheDirectory =
            options.cacheDirectory.empty() ? outputDirectory / ".iblbake-cache" : options.cacheDirectory;
        outputs.createDirectories(cacheDirectory, scene.name + ": cache");
        const StageCache cache(cacheDirectory);
        // Compiled kernels beside the entries (docs/conventions.md "Kernels, backends and kernel binaries"):
        // a node with a warm cache compiles none; and in the user's cache, so that a new bake on this machine
        // compiles none either.
        if (executor && executor->usesOpenCL()) {
            std::vector<fs::path> programBinaries{cache.directory() / "kernels"};
            if (const std::optional<fs::path> user = ocl::userProgramBinaryDirectory())
                programBinaries.push_back(*user);
            executor->cl().useProgramBinaries(std::move(programBinaries));
        }

        StageRun run = runStages(
            {scene.name, cache, [&] { return executor ? &*executor : nullptr; }, options.force, progress},
            plan, summary.stages, current);
        const std::map<std::string, fs::path>& entries = run.entries;

        outputs.createDirectories(outputDirectory, scene.name + ": outputs.directory");
        ManifestInputs manifest{scene, plan, entries, keys, {}, summary.backend};
        const fs::path manifestPath = outputDirectory / "manifest.json";
        try {
            manifest.productHashes =
                stageProducts(plan, entries, outputDirectory, scene.outputs.directory, outputs, summary);
            const nlohmann::json document = buildManifest(manifest);
            summary.storage = storedProductsFromManifest(document);
            outputs.writeFile(manifestPath, [&](const fs::path& temporary) {
                writeFileBytes(temporary, document.dump(2) + '\n', manifestPath.string());
            });
            // Everything is written: commit the cache entries, then the products, the manifest last (a bake
            // killed in between leaves the old manifest, which points only at files that are still there).
            for (StagedEntry& staged : run.ran)
                cache.commit(staged);
            outputs.commit();
        } catch (const OutputError& e) { // a full disk, a read-only directory: the scene in front
            throw OutputError(scene.name + ": " + e.what());
        }
        if (executor && executor->usesOpenCL()) executor->cl().storeProgramBinaries();
        summary.products.push_back(scene.outputs.directory / "manifest.json");
        summary.manifest = scene.outputs.directory / "manifest.json";
        summary.ok = true;
        addManifestReport(summary);
    } catch (const std::exception& e) { // ibl::Error, and anything a library throws: one line, no crash
        summary.ok = false;
        summary.error = replaceAll(e.what(), openedDirectory, scene.outputs.directory.string());
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
    // A scene refused before any work is found not up to date without its inputs hashed, and bakeStages
    // refuses it (refusalBeforeWork).
    const UpToDate checked = checkBakeUpToDate(scene, options); // "--force" when forced: never up to date
    if (checked.upToDate) return reportUpToDateBake(scene, checked, progress, start);
    return bakeStages(scene, options, progress, checked.inputHashes, start);
}

BakeSummary bakeStaleScene(const Scene& scene, const BakeOptions& options, ProgressSink& progress,
                           const UpToDate& checked) {
    return bakeStages(scene, options, progress, checked.inputHashes, std::chrono::steady_clock::now());
}

} // namespace ibl
