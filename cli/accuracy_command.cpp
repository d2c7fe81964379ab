// iblbake accuracy: sweeps every stage's quality knobs on the user's input, times each setting and measures
// its error against the brute-force reference; writes report.json, report.md and report.html into a
// directory that appears only when complete.
#include "report.h"
#include "sweep.h"
#include "commands.h"
#include "common_options.h"
#include "input_options.h"

#include <iblbake/error.h>
#include <iblbake/ingest.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <thread>
#include <unistd.h>

namespace fs = std::filesystem;

namespace ibl::cli {

namespace {

struct AccuracyOptions {
    InputOptions input;
    std::string output;
    int repeats = 3;
    bool quick = false;
    BackendOptions backend;
};

std::string loadAverage() {
    std::ifstream in("/proc/loadavg");
    double one = 0, five = 0, fifteen = 0;
    if (!(in >> one >> five >> fifteen)) return "unknown";
    char text[64];
    std::snprintf(text, sizeof text, "%.2f %.2f %.2f", one, five, fifteen);
    return text;
}

void writeText(const fs::path& file, const std::string& text) {
    std::ofstream out(file, std::ios::binary);
    out << text;
    out.close();
    if (!out) throw Error(file.string() + ": cannot write");
}

// Writes the reports into a temporary sibling of `dir` and renames it to `dir`; an existing directory keeps
// its other files and gets each report by a rename of its own, so no reader sees a partial report.
void commitReports(const fs::path& dir, const AccuracyRun& run) {
    const fs::path target = fs::absolute(dir);
    fs::create_directories(target.parent_path());
    const fs::path temp =
        target.parent_path() / (target.filename().string() + ".tmp-" + std::to_string(getpid()));
    fs::remove_all(temp);
    fs::create_directory(temp);
    try {
        writeText(temp / "report.json", accuracyJson(run));
        writeText(temp / "report.md", accuracyMarkdown(run));
        writeText(temp / "report.html", accuracyHtml(run));
        if (!fs::exists(target)) {
            fs::rename(temp, target);
            return;
        }
        for (const char* name : {"report.json", "report.md", "report.html"})
            fs::rename(temp / name, target / name);
        fs::remove(temp);
    } catch (...) {
        std::error_code ignored;
        fs::remove_all(temp, ignored);
        throw;
    }
}

void printStage(const AccuracyStage& stage) {
    std::printf("%-32s %zu settings:", stage.title.c_str(), stage.settings.size());
    for (const MeasuredSetting& s : stage.settings)
        if (!s.preset.empty()) std::printf("  %s %.3g ms %.3g%%", s.preset.c_str(), s.timeMs, 100 * s.error);
    std::printf("\n");
    std::fflush(stdout);
}

} // namespace

Action addAccuracyCommand(CLI::App& app) {
    auto o = std::make_shared<AccuracyOptions>();
    CLI::App* cmd = app.add_subcommand(
        "accuracy", "sweep every stage's quality knobs: time and error against the brute-force reference");
    o->input.addTo(*cmd);
    cmd->add_option("-o,--output", o->output, "report directory (report.json, report.md, report.html)")
        ->required();
    cmd->add_option("--repeats", o->repeats, "timed runs per setting (the median is reported)")
        ->capture_default_str()
        ->check(CLI::Range(1, 100));
    cmd->add_flag("--quick", o->quick, "a small sweep at tiny sizes (seconds; what the tests run)");
    o->backend.addTo(*cmd);

    return [o] {
        const auto start = std::chrono::steady_clock::now();
        if (fs::exists(o->output) && !fs::is_directory(o->output))
            throw Error(o->output + ": exists and is not a directory");
        const SweepPlan plan = o->quick ? SweepPlan::quick() : SweepPlan::full();
        AccuracyRun run;
        run.quick = o->quick;
        run.repeats = o->repeats;
        run.sourceFaceSize = plan.sourceFaceSize;
        run.hardwareThreads = std::thread::hardware_concurrency();
        const std::string loadAtStart = loadAverage();
        auto load = [&](int faceSize) {
            return ingestEnvironment(o->input.files(), o->input.settings(faceSize)).cube;
        };
        const SourceEnvironment env =
            ingestEnvironment(o->input.files(), o->input.settings(plan.sourceFaceSize));
        run.input = fs::path(env.report.file).filename().string();
        printIngestReport(env.report);
        Executor executor = o->backend.makeExecutor();
        run.backend = executor.description();

        run.stages.push_back(measureDfg(plan, o->repeats, executor));
        printStage(run.stages.back());
        run.stages.push_back(measureSpecular(plan, load, o->repeats, executor));
        printStage(run.stages.back());
        run.stages.push_back(measureSpecularConvergence(plan, load, o->repeats, executor));
        printStage(run.stages.back());
        for (AccuracyStage& stage : measureDiffuse(plan, env.cube, o->repeats, executor)) {
            run.stages.push_back(std::move(stage));
            printStage(run.stages.back());
        }
        run.stages.push_back(measureRuntime(plan, env.cube, o->repeats, executor));
        printStage(run.stages.back());

        run.load = "start " + loadAtStart + ", end " + loadAverage();
        run.totalSeconds = millisecondsSince(start) / 1000.0;
        commitReports(o->output, run);
        std::printf("wrote   %s/report.json, report.md, report.html (%.1f s, load average %s)\n",
                    o->output.c_str(), run.totalSeconds, run.load.c_str());
        return 0;
    };
}

} // namespace ibl::cli
