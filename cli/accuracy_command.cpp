// iblbake accuracy INPUT -o DIR: reads the input as the other commands do, runs the library's sweep
// (iblbake/accuracy/accuracy.h) with one line per stage as it is measured, and writes the reports into DIR.
#include "commands.h"
#include "common_options.h"
#include "input_options.h"

#include <iblbake/accuracy/accuracy.h>
#include <iblbake/baker/ingest.h>
#include <iblbake/baker/inspect.h>
#include <iblbake/core/error.h>

#include <chrono>
#include <cstdio>
#include <filesystem>

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

void printStage(const AccuracyStage& stage) {
    std::printf("%-32s %zu settings:", stage.title.c_str(), stage.settings.size());
    for (const MeasuredSetting& s : stage.settings)
        if (!s.preset.empty()) std::printf("  %s %.3g ms %.3g%%", s.preset.c_str(), s.timeMs, 100 * s.error);
    std::printf("\n");
    std::fflush(stdout);
}

} // namespace

Action addAccuracyCommand(CLI::App& app) {
    auto [o, cmd] = addInputSubcommand<AccuracyOptions>(
        app, "accuracy",
        "sweep every stage's quality knobs: time and error against the brute-force reference",
        "report directory (report.json, report.md, report.html)");
    cmd->add_option("--repeats", o->repeats, "timed runs per setting (the median is reported)")
        ->capture_default_str()
        ->check(CLI::Range(1, 100));
    cmd->add_flag("--quick", o->quick, "a small sweep at tiny sizes (seconds; what the tests run)");
    o->backend.addTo(*cmd);

    return [o = o] {
        const auto start = std::chrono::steady_clock::now();
        if (fs::exists(o->output) && !fs::is_directory(o->output))
            throw Error(o->output + ": exists and is not a directory");
        const SweepPlan plan = o->quick ? SweepPlan::quick() : SweepPlan::full();
        SourceEnvironment env = ingestEnvironment(o->input.files(), o->input.settings(plan.sourceFaceSize));
        std::printf("%s", ingestReportText(env.report).c_str());
        const AccuracyInput input{
            fs::path(env.report.file).filename().string(), std::move(env.cube), [&](int faceSize) {
                return ingestEnvironment(o->input.files(), o->input.settings(faceSize)).cube;
            }};
        const Executor executor = o->backend.makeExecutor();
        const AccuracyRun run = runAccuracySweep(plan, input, o->repeats, executor, printStage, start);
        writeAccuracyReports(o->output, run);
        BackendOptions::storeBuiltKernels(executor);
        std::printf("wrote   %s/report.json, report.md, report.html (%.1f s, load average %s)\n",
                    o->output.c_str(), run.totalSeconds, run.load.c_str());
        return 0;
    };
}

} // namespace ibl::cli
