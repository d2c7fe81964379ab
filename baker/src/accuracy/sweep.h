// The stages of the accuracy sweep (iblbake/accuracy/accuracy.h), one function each, and what they share.
#pragma once

#include "iblbake/accuracy/accuracy.h"

#include <functional>
#include <string>
#include <vector>

namespace ibl {

AccuracyStage measureDfg(const SweepPlan& plan, int repeats, const Executor& executor);
AccuracyStage measureSpecular(const SweepPlan& plan, const CubeLoader& load, int repeats,
                              const Executor& executor);
AccuracyStage measureSpecularProduction(const SweepPlan& plan, const CubeMap& source, int repeats,
                                        const Executor& executor);
// The SH and the irradiance cube share their reference (referenceIrradianceCube).
std::vector<AccuracyStage> measureDiffuse(const SweepPlan& plan, const CubeMap& source, int repeats,
                                          const Executor& executor);
AccuracyStage measureRuntime(const SweepPlan& plan, const CubeMap& source, int repeats,
                             const Executor& executor);

// Marks the settings no other setting of the stage beats in both time and error (ties in both keep both).
void markParetoFront(AccuracyStage& stage);

// Runs `work` `repeats` times and returns each run's wall time in milliseconds.
std::vector<double> timeRuns(int repeats, const std::function<void()>& work);
double median(std::vector<double> values);

// Runs `bake` `repeats` times into s.timesMs (their median into s.timeMs) and returns the last run's result.
template <class Bake>
auto timedBake(MeasuredSetting& s, int repeats, Bake&& bake) {
    decltype(bake()) result;
    s.timesMs = timeRuns(repeats, [&] { result = bake(); });
    s.timeMs = median(s.timesMs);
    return result;
}

// A stage with its name, title and knobs, for a measuring function to describe further and fill.
AccuracyStage namedStage(std::string name, std::string title, std::vector<std::string> knobs);

} // namespace ibl
