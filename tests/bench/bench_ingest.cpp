// Ingest time (Google Benchmark; never a pass/fail timer): the whole ingest of the sample HDRI (read,
// repair, colour, exact-area lat-long -> cube resampling) at n-texel faces, alone and with the measurements
// made on the cube before a bake (statistics, sun detection, zenith luminance), and each step on its own.
// Process CPU time is reported beside wall time: on a shared 2-core machine it is the steadier figure.
#include "bench_sample.h"
#include "cube_texel_geometry.h"
#include "ingest_internal.h"

#include <iblbake/baker/calibration.h>
#include <iblbake/baker/environment_stats.h>
#include <iblbake/baker/ingest.h>
#include <iblbake/baker/sun.h>

#include <benchmark/benchmark.h>

namespace {

// The sample read and repaired once: the steps after the read start from it.
const ibl::ingest::RawImage& sampleImage() {
    static const ibl::ingest::RawImage image = [] {
        ibl::ingest::RawImage raw = ibl::ingest::readImage(IBLBAKE_SAMPLE_HDRI);
        ibl::ingest::sanitize(raw.pixels);
        return raw;
    }();
    return image;
}

void ingestSample(benchmark::State& state) {
    ibl::IngestSettings settings;
    settings.sourceFaceSize = int(state.range(0));
    for (auto _ : state)
        benchmark::DoNotOptimize(ibl::ingestEnvironment({IBLBAKE_SAMPLE_HDRI}, settings));
}

void ingestRead(benchmark::State& state) {
    for (auto _ : state)
        benchmark::DoNotOptimize(ibl::ingest::readImage(IBLBAKE_SAMPLE_HDRI));
}

// A repaired image again: the same checks of every value, nothing left to change.
void ingestSanitize(benchmark::State& state) {
    ibl::ImageRGBA image = sampleImage().pixels;
    for (auto _ : state)
        benchmark::DoNotOptimize(ibl::ingest::sanitize(image));
}

// Rec.709 -> ACEScg (the sample is Rec.709, where the default working space makes this step a no-op);
// converted back and forth so that every iteration sees the same values.
void ingestColour(benchmark::State& state) {
    ibl::ImageRGBA image = sampleImage().pixels;
    for (auto _ : state) {
        ibl::ingest::convertColor(image, "lin_rec709", "acescg", "sample");
        ibl::ingest::convertColor(image, "acescg", "lin_rec709", "sample");
    }
    state.SetLabel("two conversions");
}

void ingestMaxLuminance(benchmark::State& state) {
    for (auto _ : state)
        benchmark::DoNotOptimize(ibl::ingest::maxLuminance(sampleImage().pixels, ibl::kRec709Luminance));
}

void ingestResample(benchmark::State& state) {
    const ibl::ImageRGBA& image = sampleImage().pixels;
    for (auto _ : state)
        benchmark::DoNotOptimize(ibl::ingest::resampleLatLongToCubeRotated(image, int(state.range(0)),
                                                                           ibl::LatLongPixels::Centre, 0.0));
}

// The same from the Radiance file's RGBE pixels as stored (what ingestEnvironment resamples from a .hdr).
void ingestResampleRgbe(benchmark::State& state) {
    static const ibl::ingest::ImageRGBE image =
        ibl::ingest::readImage(IBLBAKE_SAMPLE_HDRI, nullptr, false, true).rgbe;
    for (auto _ : state)
        benchmark::DoNotOptimize(ibl::ingest::resampleLatLongToCubeRotated(image, int(state.range(0)),
                                                                           ibl::LatLongPixels::Centre, 0.0));
}

// The table of one face size that statistics, sun detection and zenith luminance read (built once per
// process and face size; their benchmarks reuse it).
void cubeTexelGeometry(benchmark::State& state) {
    for (auto _ : state)
        benchmark::DoNotOptimize(ibl::CubeTexelGeometry(int(state.range(0))));
}

void cubeStatistics(benchmark::State& state) {
    const ibl::CubeMap& cube = ibl::bench::sampleCube(int(state.range(0)));
    for (auto _ : state)
        benchmark::DoNotOptimize(ibl::computeEnvironmentStats(cube, ibl::kRec709Luminance));
}

// The part of the statistics a calibration reads (computeCalibration).
void cubeTotals(benchmark::State& state) {
    const ibl::CubeMap& cube = ibl::bench::sampleCube(int(state.range(0)));
    for (auto _ : state)
        benchmark::DoNotOptimize(
            ibl::computeEnvironmentTotals(ibl::SphereTexels(cube), ibl::kRec709Luminance));
}

void cubeSunDetection(benchmark::State& state) {
    const ibl::CubeMap& cube = ibl::bench::sampleCube(int(state.range(0)));
    for (auto _ : state)
        benchmark::DoNotOptimize(ibl::detectSun(cube, ibl::SunDetectSettings{}));
}

void cubeZenithLuminance(benchmark::State& state) {
    const ibl::CubeMap& cube = ibl::bench::sampleCube(int(state.range(0)));
    for (auto _ : state)
        benchmark::DoNotOptimize(
            ibl::zenithLuminance(ibl::SphereTexels(cube), ibl::kZenithCapDegrees, ibl::kRec709Luminance));
}

// The whole of issue 18 item 2's budget: the ingest (read, repair, colour, resampling into n-texel faces)
// and the measurements a calibration makes on its cube (the statistics' totals computeCalibration reads,
// sun detection, zenith luminance without the sun's texels).
void ingestAndMeasure(benchmark::State& state) {
    ibl::IngestSettings settings;
    settings.sourceFaceSize = int(state.range(0));
    for (auto _ : state) {
        const ibl::SourceEnvironment env = ibl::ingestEnvironment({IBLBAKE_SAMPLE_HDRI}, settings);
        const ibl::SphereTexels texels(env.cube);
        benchmark::DoNotOptimize(ibl::computeEnvironmentTotals(texels, ibl::kRec709Luminance));
        const ibl::SunDetection sun = ibl::detectSun(texels, ibl::SunDetectSettings{});
        benchmark::DoNotOptimize(
            ibl::zenithLuminance(texels, ibl::kZenithCapDegrees, ibl::kRec709Luminance, sun.region));
    }
}

BENCHMARK(ingestSample)->Arg(64)->Arg(256)->Arg(1024)->Apply(ibl::bench::wallAndCpuMilliseconds);
BENCHMARK(ingestAndMeasure)->Arg(256)->Apply(ibl::bench::wallAndCpuMilliseconds);
BENCHMARK(ingestRead)->Apply(ibl::bench::wallAndCpuMilliseconds);
BENCHMARK(ingestSanitize)->Apply(ibl::bench::wallAndCpuMilliseconds);
BENCHMARK(ingestColour)->Apply(ibl::bench::wallAndCpuMilliseconds);
BENCHMARK(ingestMaxLuminance)->Apply(ibl::bench::wallAndCpuMilliseconds);
BENCHMARK(ingestResample)->Arg(256)->Apply(ibl::bench::wallAndCpuMilliseconds);
BENCHMARK(ingestResampleRgbe)->Arg(256)->Apply(ibl::bench::wallAndCpuMilliseconds);
BENCHMARK(cubeTexelGeometry)->Arg(256)->Apply(ibl::bench::wallAndCpuMilliseconds);
BENCHMARK(cubeStatistics)->Arg(256)->Apply(ibl::bench::wallAndCpuMilliseconds);
BENCHMARK(cubeTotals)->Arg(256)->Apply(ibl::bench::wallAndCpuMilliseconds);
BENCHMARK(cubeSunDetection)->Arg(256)->Apply(ibl::bench::wallAndCpuMilliseconds);
BENCHMARK(cubeZenithLuminance)->Arg(256)->Apply(ibl::bench::wallAndCpuMilliseconds);

} // namespace
