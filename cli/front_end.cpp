// iblbake: the front end. `iblbake plan SCENE` (pure), `iblbake bake SCENE` on a scene whose bake directory
// is up to date, and `iblbake batch MANIFEST` when every item of the shard is, are answered here, from the
// scene, manifest.json and content hashes alone; every other command line goes, unchanged, to the engine
// (iblbake-engine beside this program, or $IBLBAKE_ENGINE) by exec. Why two programs: the engine links
// OpenColorIO, OpenEXR, TBB and the OpenCL loader, which the dynamic loader maps and relocates in about as
// long as the whole up-to-date check takes (10 ms here against the engine's 17 ms, docs/performance.md
// "Scenes, the front end and the cache").
#include "bake_options.h"
#include "batch_options.h"
#include "plan_command.h"

#include <iblbake/bake_state/bake_state.h>
#include <iblbake/bake_state/console_progress.h>
#include <iblbake/scene/scene.h>

#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <unistd.h>

namespace {

namespace fs = std::filesystem;

// The exit code when the bake is up to date and reported; nullopt when the engine must answer: any other
// command, --force, --help, a parse error, a bad scene (the engine gives the one-line error), a stale bake.
std::optional<int> answerUpToDateBake(int argc, char** argv) {
    const auto start = std::chrono::steady_clock::now();
    CLI::App app{"iblbake", "iblbake"};
    ibl::cli::BakeCommandOptions options;
    ibl::cli::addBakeSubcommand(app, options);
    try {
        app.parse(argc, argv);
        if (options.force) return std::nullopt;
        const ibl::Scene scene = options.loadScene();
        const ibl::UpToDate upToDate = ibl::checkBakeUpToDate(scene, options.bakeOptions());
        if (!upToDate.upToDate) return std::nullopt;
        ibl::ConsoleProgress progress(ibl::chooseProgressMode(options.quiet, options.json));
        ibl::reportUpToDateBake(scene, upToDate, progress, start);
        return 0;
    } catch (...) { // CLI::ParseError, CLI::Success (--help), ibl::Error: the engine reports them
        return std::nullopt;
    }
}

// The same for a batch: answered when every item of the shard is up to date (then the library's runBatch
// finds nothing to bake and only writes the summary); a failure after that point is reported here, as the
// engine would.
std::optional<int> answerUpToDateBatch(int argc, char** argv) {
    CLI::App app{"iblbake", "iblbake"};
    ibl::cli::BatchCommandOptions options;
    ibl::cli::addBatchSubcommand(app, options);
    ibl::BatchManifest manifest;
    ibl::Shard shard;
    ibl::KnownUpToDate known;
    try {
        app.parse(argc, argv);
        if (options.force) return std::nullopt;
        manifest = ibl::loadBatchManifest(options.manifest);
        shard = ibl::cli::chooseShard(options);
        std::optional<ibl::KnownUpToDate> allUpToDate =
            ibl::shardUpToDate(manifest, shard, options.bakeOptions());
        if (!allUpToDate) return std::nullopt;
        known = std::move(*allUpToDate);
    } catch (...) {
        return std::nullopt;
    }
    const auto needsEngine = [](const ibl::Scene&, const ibl::BakeOptions&, ibl::ProgressSink&,
                                const ibl::UpToDate&) -> ibl::BakeSummary {
        throw std::logic_error("the front end was asked to bake"); // every item was found up to date
    };
    try {
        return ibl::cli::runBatchCommand(options, manifest, shard, needsEngine, known);
    } catch (const std::exception& e) { // the summary could not be written
        std::fprintf(stderr, "iblbake: error: %s\n", e.what());
        return 1;
    }
}

// A plan, unless the scene is bad (the engine gives the one-line error) or the command line needs help.
std::optional<int> answerPlan(int argc, char** argv) {
    CLI::App app{"iblbake", "iblbake"};
    ibl::cli::PlanOptions options;
    ibl::cli::addPlanSubcommand(app, options);
    try {
        app.parse(argc, argv);
        return ibl::cli::runPlan(options); // prints only once the scene has parsed and planned
    } catch (...) {
        return std::nullopt;
    }
}

fs::path enginePath() {
    if (const char* path = std::getenv("IBLBAKE_ENGINE"); path && *path) return path;
    std::error_code ec;
    const fs::path self = fs::read_symlink("/proc/self/exe", ec);
    return (ec ? fs::path("iblbake-engine") : self.parent_path() / "iblbake-engine");
}

// The engine's environment with glibc's malloc asked to back its heap with transparent huge pages
// (glibc.malloc.hugetlb=1, read only at a process's start, hence set here for the engine), unless the
// caller's GLIBC_TUNABLES already chooses: a bake first touches 20-60 MB of blocks (a lat-long, a cube, its
// pyramid, the levels), one page fault per 4 KB page and 3-13 us each on the VM the benchmarks ran on; in
// 2 MB pages, `specular` of the 1k sample took 5,100 -> 716-1,602 page faults and 0.17-0.19 -> 0.12-0.16 s
// (peak memory 30.1-30.3 -> 30.5-32.2 MB; docs/performance.md "Memory"). The rest of the
// allocator policy is the engine's (iblbake/baker/process_memory.h). Where the kernel gives no huge pages
// (transparent_hugepage "never"), nothing changes.
std::string tunablesWithHugePages(const char* current) {
    const std::string tunables = current ? current : "";
    if (tunables.find("glibc.malloc.hugetlb=") != std::string::npos) return tunables;
    return tunables + (tunables.empty() ? "" : ":") + "glibc.malloc.hugetlb=1";
}

} // namespace

int main(int argc, char** argv) {
    if (argc >= 2 && std::string_view(argv[1]) == "plan")
        if (const std::optional<int> exitCode = answerPlan(argc, argv)) return *exitCode;
    if (argc >= 2 && std::string_view(argv[1]) == "bake")
        if (const std::optional<int> exitCode = answerUpToDateBake(argc, argv)) return *exitCode;
    if (argc >= 2 && std::string_view(argv[1]) == "batch")
        if (const std::optional<int> exitCode = answerUpToDateBatch(argc, argv)) return *exitCode;
    const fs::path engine = enginePath();
    ::setenv("GLIBC_TUNABLES", tunablesWithHugePages(std::getenv("GLIBC_TUNABLES")).c_str(), 1);
    ::execvp(engine.c_str(), argv); // a bare name (no /proc) is looked up in PATH
    std::fprintf(stderr, "iblbake: error: cannot run the engine %s: %s\n", engine.c_str(),
                 std::strerror(errno));
    return 1;
}
