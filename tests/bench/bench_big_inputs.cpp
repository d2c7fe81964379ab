// Big HDRIs (docs/performance.md "Big HDRIs"; Google Benchmark, never a pass/fail timer): each kind of input
// at 8k x 4k and 16k x 8k, timed three ways on the same file: OpenImageIO's decode with 2 threads
// (ImageInput::read_image, all channels to float, as `oiiotool` and OpenImageIO's Python read_image), our
// decode alone (the blocks the streamed ingest decodes and repairs, no resampling), our ingest to 1,024-px
// faces (ingestEnvironment: decode, repair, colour, resampling), and the whole `iblbake specular FILE -o
// X.ktx2 --size 1024` in a child process with its peak RSS. Registered only when $IBLBAKE_BENCH_BIG_DIR names
// a directory: the inputs (the README's sample resized by OpenImageIO, as `oiiotool --resize`; Radiance, half
// and float OpenEXR with ZIP compression, tiled half OpenEXR) are written there on first use, 2.5 GB in all,
// and reused; $IBLBAKE_BENCH_BIG_SOURCE names another HDRI to resize.
#include "ingest_internal.h"

#include <iblbake/baker/calibration.h>
#include <iblbake/baker/ingest.h>

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <OpenImageIO/imageio.h>
#include <benchmark/benchmark.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <fcntl.h>
#include <spawn.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

extern char** environ;

namespace {

namespace fs = std::filesystem;

struct InputKind {
    const char* name;
    const char* extension;
    OIIO::TypeDesc format;
    int tile; // 0: scan lines
};

constexpr InputKind kKinds[] = {{"hdr", ".hdr", OIIO::TypeDesc::FLOAT, 0},
                                {"half", ".exr", OIIO::TypeDesc::HALF, 0},
                                {"float", ".exr", OIIO::TypeDesc::FLOAT, 0},
                                {"tiled-half", ".exr", OIIO::TypeDesc::HALF, 64}};
constexpr int kWidths[] = {8192, 16384};

// The input of a kind and width, written on first use.
fs::path bigInput(const fs::path& dir, const InputKind& kind, int width) {
    const fs::path file = dir / ("latlong-" + std::to_string(width) + "-" + kind.name + kind.extension);
    if (fs::exists(file)) return file;
    const char* source = std::getenv("IBLBAKE_BENCH_BIG_SOURCE");
    const OIIO::ImageBuf sample(source && *source ? source : IBLBAKE_SAMPLE_HDRI);
    const OIIO::ImageBuf resized =
        OIIO::ImageBufAlgo::resize(sample, "", 0.0f, OIIO::ROI(0, width, 0, width / 2));
    OIIO::ImageSpec spec(width, width / 2, 3, kind.format);
    spec.attribute("compression", "zip");
    if (kind.tile > 0) spec.tile_width = spec.tile_height = kind.tile;
    fs::path part = file;
    part.replace_extension(std::string(".part") +
                           kind.extension); // OpenImageIO picks the writer by extension
    auto out = OIIO::ImageOutput::create(part.string());
    if (!out || !out->open(part.string(), spec) || !resized.write(out.get()) || !out->close())
        throw std::runtime_error("cannot write " + part.string() + ": " + OIIO::geterror());
    fs::rename(part, file);
    return file;
}

// OpenImageIO's decode of every channel to float with 2 threads, into a buffer reused across iterations (its
// page faults are not OpenImageIO's).
void oiioDecode(benchmark::State& state, const fs::path& file) {
    std::vector<float> pixels;
    for (auto _ : state) {
        auto in = OIIO::ImageInput::open(file.string());
        if (!in) throw std::runtime_error("cannot open " + file.string());
        in->threads(2);
        const OIIO::ImageSpec& spec = in->spec();
        pixels.resize(std::size_t(spec.width) * std::size_t(spec.height) * std::size_t(spec.nchannels));
        if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, pixels.data()))
            throw std::runtime_error("cannot read " + file.string());
    }
}

void ingest(benchmark::State& state, const fs::path& file) {
    ibl::IngestSettings settings;
    settings.sourceFaceSize = 1024;
    for (auto _ : state)
        benchmark::DoNotOptimize(ibl::ingestEnvironment({file}, settings));
}

// The whole command in a child process, under /usr/bin/time for its peak RSS (the engine it execs included;
// the child of a spawn would report this process's own until its exec) as the counter peakMiB.
void wholeCommand(benchmark::State& state, const fs::path& file) {
    const fs::path dir = file.parent_path(), peakFile = dir / "bench-peak.txt";
    std::vector<std::string> args = {
        "/usr/bin/time", "-f",       "%M",          "-o", peakFile.string(),
        IBLBAKE_CLI,     "specular", file.string(), "-o", (dir / "bench.ktx2").string(),
        "--size",        "1024"};
    std::vector<char*> argv;
    for (std::string& a : args)
        argv.push_back(a.data());
    argv.push_back(nullptr);
    posix_spawn_file_actions_t quiet; // the command's report lines would break up the benchmark's table
    posix_spawn_file_actions_init(&quiet);
    posix_spawn_file_actions_addopen(&quiet, STDOUT_FILENO, "/dev/null", O_WRONLY, 0);
    double peakMiB = 0.0;
    for (auto _ : state) {
        pid_t child = 0;
        if (posix_spawn(&child, argv[0], &quiet, nullptr, argv.data(), environ) != 0)
            throw std::runtime_error("cannot run /usr/bin/time");
        int status = 0;
        waitpid(child, &status, 0);
        if (!WIFEXITED(status) || WEXITSTATUS(status) != 0)
            throw std::runtime_error("iblbake specular " + file.string() + " failed");
        double kilobytes = 0.0;
        std::ifstream(peakFile) >> kilobytes;
        peakMiB = std::max(peakMiB, kilobytes / 1024.0);
    }
    posix_spawn_file_actions_destroy(&quiet);
    state.counters["peakMiB"] = peakMiB;
}

// Our decode alone: every block of an OpenEXR file decoded and repaired as the streamed ingest does
// (RepairedLatLongBlocks), with no resampling; a Radiance file read whole as its RGBE bytes.
void decodeBlocks(benchmark::State& state, const fs::path& file) {
    for (auto _ : state) {
        ibl::ingest::OpenedImage image = ibl::ingest::openImage(file);
        if (!image.source->readsRowsInAnyOrder()) {
            ibl::ingest::readPixels(image, true);
            continue;
        }
        ibl::ingest::RepairedLatLongBlocks blocks(image, ibl::kRec709Luminance, nullptr,
                                                  ibl::ingest::defaultBlockPixels(image.raw.pixels.width));
        blocks.decodeRest();
    }
}

const bool registered = [] {
    const char* dir = std::getenv("IBLBAKE_BENCH_BIG_DIR");
    if (!dir || !*dir) return false;
    fs::create_directories(dir);
    for (int width : kWidths)
        for (const InputKind& kind : kKinds) {
            const fs::path file = bigInput(dir, kind, width);
            const std::string suffix = std::string("/") + kind.name + "/" + std::to_string(width);
            for (auto [name, run] :
                 {std::pair{"bigOiioDecode", &oiioDecode}, std::pair{"bigDecode", &decodeBlocks},
                  std::pair{"bigIngest", &ingest}, std::pair{"bigCommand", &wholeCommand}})
                benchmark::RegisterBenchmark((name + suffix).c_str(), run, file)
                    ->Unit(benchmark::kMillisecond)
                    ->UseRealTime()
                    ->Iterations(1);
        }
    return true;
}();

} // namespace
