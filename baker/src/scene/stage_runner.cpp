// runStages (stage_runner.h).
#include "stage_runner.h"

#include "iblbake/core/error.h"
#include "scene_stages.h"

#include <chrono>
#include <optional>

namespace ibl {

namespace fs = std::filesystem;

StageRun runStages(const StageRunner& runner, const Plan& plan, std::vector<StageResult>& results,
                   std::size_t& current) {
    StageRun run;
    const Executor* executor = nullptr;
    const int count = int(plan.stages.size());
    for (current = 0; current < plan.stages.size(); ++current) {
        const PlanStage& stage = plan.stages[current];
        StageResult& result = results[current];
        runner.progress.stageStart(result, int(current), count);
        const auto start = std::chrono::steady_clock::now();
        std::optional<fs::path> entry;
        if (!runner.force) entry = runner.cache.find(result.key);
        if (entry) {
            result.status = StageStatus::Cached;
        } else {
            if (stage.usesBackend && !executor) executor = runner.executor();
            StagedEntry& staged = run.ran.emplace_back(runner.cache.staging(result.key));
            StageContext context{runner.name, stage, {}, executor, staged.directory()};
            context.waiting = [&](const std::string& what, const std::string& detail, double secondsLeft) {
                runner.progress.stageWaiting(result, what, detail, secondsLeft);
            };
            if (executor && executor->usesOpenCL())
                executor->cl().setCompileObserver([&](const std::string& file, double seconds) {
                    runner.progress.stageWaiting(result, "compile",
                                                 "kernels/" + file + ", first use on this device and driver",
                                                 seconds);
                });
            for (const std::string& dependency : stage.dependsOn)
                context.dependencies[dependency] = run.entries.at(dependency);
            try {
                runStage(context);
                runner.cache.seal(staged);
            } catch (const OutputError& e) { // a full disk, a read-only directory: the name in front
                throw OutputError(runner.name + ": " + e.what());
            }
            entry = staged.directory();
            result.status = StageStatus::Ran;
        }
        run.entries[stage.id] = *entry;
        result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        runner.progress.stageEnd(result, int(current), count);
    }
    return run;
}

} // namespace ibl
