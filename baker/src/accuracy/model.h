// `iblbake accuracy`: what one measured setting and one stage's sweep hold, shared by the sweep
// (accuracy_sweep.cpp) and the report writers (accuracy_report.cpp, accuracy_html.cpp).
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace ibl::cli {

struct MeasuredSetting {
    std::string label;                                      // e.g. "256 spp, bias -0.5, 32 px"
    std::vector<std::pair<std::string, std::string>> knobs; // name -> value (JSON: a number when numeric)
    std::string preset;          // "draft", "production", "reference", "default" or ""
    double timeMs = 0.0;         // median of the repeats
    std::vector<double> timesMs; // every repeat
    double error = 0.0;          // the stage's summary error (what the plot's y axis shows), a fraction
    double maxError = 0.0;       // see AccuracyStage::maxErrorMetric
    double energyError = 0.0;    // see AccuracyStage::energyErrorMetric
    // Per part of the output, when the stage has parts (specular: per level; runtime: per roughness).
    std::vector<std::pair<std::string, double>> partErrors;
    bool pareto = false; // on the time/error Pareto front of its stage
};

struct AccuracyStage {
    std::string name;  // "dfg", "specular", "sh", "irradiance", "runtime"
    std::string title; // for the report
    std::vector<std::string> knobs;
    std::string reference;         // what the settings are compared with
    std::string errorMetric;       // the summary error
    std::string maxErrorMetric;    // maxError
    std::string energyErrorMetric; // energyError
    std::string timeMeaning;       // what is timed
    std::vector<MeasuredSetting> settings;
};

struct AccuracyRun {
    std::string input;
    int sourceFaceSize = 0;
    bool quick = false;
    int repeats = 0;
    std::string backend;
    std::string load; // /proc/loadavg at the start and the end
    unsigned hardwareThreads = 0;
    double totalSeconds = 0.0;
    std::vector<AccuracyStage> stages;
};

// Marks the settings no other setting of the stage beats in both time and error (ties in both keep both).
void markParetoFront(AccuracyStage& stage);

} // namespace ibl::cli
