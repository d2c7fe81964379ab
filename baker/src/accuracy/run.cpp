// runAccuracySweep (iblbake/accuracy/accuracy.h): the stages in report order, and what the reports say about
// the machine the times were measured on.
#include "sweep.h"

#include <cstdio>
#include <fstream>
#include <thread>

namespace ibl {

namespace {

// /proc/loadavg's 1, 5 and 15 minute figures: the times mean little on a loaded machine.
std::string loadAverage() {
    std::ifstream in("/proc/loadavg");
    double one = 0, five = 0, fifteen = 0;
    if (!(in >> one >> five >> fifteen)) return "unknown";
    char text[64];
    std::snprintf(text, sizeof text, "%.2f %.2f %.2f", one, five, fifteen);
    return text;
}

} // namespace

AccuracyRun runAccuracySweep(const SweepPlan& plan, const AccuracyInput& input, int repeats,
                             const Executor& executor,
                             const std::function<void(const AccuracyStage&)>& stageMeasured,
                             std::chrono::steady_clock::time_point start) {
    AccuracyRun run;
    run.input = input.name;
    run.quick = plan.isQuick;
    run.repeats = repeats;
    run.sourceFaceSize = plan.sourceFaceSize;
    run.productionFaceSize = plan.productionFaceSize;
    run.hardwareThreads = std::thread::hardware_concurrency();
    run.backend = executor.description();
    const std::string loadAtStart = loadAverage();
    auto add = [&](AccuracyStage stage) {
        run.stages.push_back(std::move(stage));
        if (stageMeasured) stageMeasured(run.stages.back());
    };
    add(measureDfg(plan, repeats, executor));
    add(measureSpecular(plan, input.load, repeats, executor));
    const CubeMap production = input.load(plan.productionFaceSize);
    add(measureSpecularProduction(plan, production, repeats, executor));
    for (AccuracyStage& stage : measureDiffuse(plan, production, repeats, executor))
        add(std::move(stage));
    add(measureRuntime(plan, production, repeats, executor));
    run.load = "start " + loadAtStart + ", end " + loadAverage();
    run.totalSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return run;
}

} // namespace ibl
