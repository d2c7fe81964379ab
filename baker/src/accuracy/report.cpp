#include "iblbake/accuracy/accuracy.h"

#include <nlohmann/json.hpp>

#include <cstdio>
#include <cstdlib>
#include <sstream>

namespace ibl {

namespace {

// A knob value as JSON: a number when the whole text is one.
nlohmann::json knobValue(const std::string& text) {
    char* end = nullptr;
    double value = std::strtod(text.c_str(), &end);
    if (!text.empty() && end == text.c_str() + text.size()) return value;
    return text;
}

std::string percent(double fraction) {
    char text[32];
    std::snprintf(text, sizeof text, fraction < 1e-3 ? "%.4f%%" : "%.3g%%", 100.0 * fraction);
    return text;
}

std::string milliseconds(double ms) {
    char text[32];
    std::snprintf(text, sizeof text, ms < 10 ? "%.2f ms" : "%.0f ms", ms);
    return text;
}

} // namespace

std::string accuracyJson(const AccuracyRun& run) {
    nlohmann::json stages = nlohmann::json::array();
    for (const AccuracyStage& stage : run.stages) {
        nlohmann::json settings = nlohmann::json::array();
        for (const MeasuredSetting& s : stage.settings) {
            nlohmann::json knobs = nlohmann::json::object(), parts = nlohmann::json::array();
            for (const auto& [name, value] : s.knobs)
                knobs[name] = knobValue(value);
            for (const auto& [name, error] : s.partErrors)
                parts.push_back({{"part", name}, {"error", error}});
            settings.push_back({{"label", s.label},
                                {"knobs", knobs},
                                {"preset", s.preset.empty() ? nlohmann::json() : nlohmann::json(s.preset)},
                                {"timeMs", s.timeMs},
                                {"timesMs", s.timesMs},
                                {"error", s.error},
                                {"maxError", s.maxError},
                                {"energyError", s.energyError},
                                {"partErrors", parts},
                                {"pareto", s.pareto}});
        }
        nlohmann::json own = nlohmann::json::array();
        for (const auto& [name, error] : stage.referenceErrors)
            own.push_back({{"part", name}, {"error", error}});
        stages.push_back({{"name", stage.name},
                          {"referenceErrorEstimate", own},
                          {"warnings", stage.warnings},
                          {"title", stage.title},
                          {"knobs", stage.knobs},
                          {"reference", stage.reference},
                          {"metrics",
                           {{"error", stage.errorMetric},
                            {"maxError", stage.maxErrorMetric},
                            {"energyError", stage.energyErrorMetric},
                            {"time", "median wall time of the repeats, ms: " + stage.timeMeaning}}},
                          {"settings", settings}});
    }
    nlohmann::json doc = {{"schema", "iblbake.accuracy"},
                          {"schemaVersion", 1},
                          {"generator", "iblbake " IBLBAKE_VERSION},
                          {"input", run.input},
                          {"sourceFaceSize", run.sourceFaceSize},
                          {"productionFaceSize", run.productionFaceSize},
                          {"quick", run.quick},
                          {"repeats", run.repeats},
                          {"backend", run.backend},
                          {"machine", {{"hardwareThreads", run.hardwareThreads}, {"loadAverage", run.load}}},
                          {"totalSeconds", run.totalSeconds},
                          {"errorsAre", "fractions (0.01 = 1%)"},
                          {"stages", stages}};
    return doc.dump(2) + "\n";
}

std::string accuracyMarkdown(const AccuracyRun& run) {
    std::ostringstream md;
    md << "## What accuracy costs in time\n\n"
       << "Input `" << run.input << "` (" << run.sourceFaceSize << " px source faces for the specular sweep, "
       << run.productionFaceSize
       << " px for the production LD chain, the SH, the irradiance cube and the runtime), " << run.backend
       << ", " << run.hardwareThreads << " hardware threads, load average (1/5/15 min) " << run.load
       << "; time = median of " << run.repeats
       << " runs. Rows: each stage's Pareto front (no other setting is both faster and more "
       << "accurate) and its presets (**bold**). Regenerate: `iblbake accuracy INPUT -o DIR` writes this "
          "table to "
       << "DIR/report.md; metrics and references are stated in DIR/report.json and DIR/report.html.\n\n"
       << "| stage | setting | time | error vs reference |\n|---|---|---|---|\n";
    for (const AccuracyStage& stage : run.stages)
        for (const MeasuredSetting& s : stage.settings) {
            if (!s.pareto && s.preset.empty()) continue;
            std::string setting = s.preset.empty() ? s.label : "**" + s.label + " (" + s.preset + ")**";
            md << "| " << stage.title << " | " << setting << " | " << milliseconds(s.timeMs) << " | "
               << percent(s.error) << " |\n";
        }
    for (const AccuracyStage& stage : run.stages)
        for (const std::string& warning : stage.warnings)
            md << "\n**Warning** (" << stage.title << "): " << warning << "\n";
    md << "\nError vs reference, per stage:\n\n";
    for (const AccuracyStage& stage : run.stages) {
        md << "- " << stage.title << ": " << stage.errorMetric << "; reference: " << stage.reference << ".";
        if (!stage.referenceErrors.empty()) {
            md << " The reference's own estimated error:";
            for (const auto& [name, error] : stage.referenceErrors)
                md << " " << name << " " << percent(error) << ";";
        }
        md << "\n";
    }
    return md.str();
}

} // namespace ibl
