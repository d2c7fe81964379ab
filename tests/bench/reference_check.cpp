// The preview's converged reference against long runs (issue 46): for an HDRI, the preview's balls at a
// given size under the map (uncalibrated: the errors are relative), the adaptive reference's stated error
// per roughness column (both rows, as the preview reports it) beside its actual difference from
// - the fixed-effort converged reference at 16x its samples and 4x its grid steps (and that run's own
//   estimate), and
// - with `samples` > 0, the every-texel brute force (renderReference) at `samples` per strategy, with its own
//   noise (its difference from itself at half the samples),
// with the time of each.
// `brightFactor` sets the converged reference's (runtime_reference.h kBrightFactor by default),
// `firstSamples` the adaptive reference's first round (AdaptiveReferenceSettings' by default).
//   reference_check HDRI [sphereSize [samples [brightFactor [firstSamples]]]]
#include <iblbake/baker/material_preview.h>
#include <iblbake/runtime/runtime_reference.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <vector>

using namespace ibl;

namespace {

double lum(const glm::dvec3& c) {
    return 0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z;
}

double secondsSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

} // namespace

int main(int argc, char** argv) try {
    if (argc < 2) {
        std::fprintf(stderr,
                     "usage: reference_check HDRI [sphereSize [samples [brightFactor [firstSamples]]]]\n");
        return 2;
    }
    MaterialPreviewSettings settings;
    settings.sphereSize = argc > 2 ? std::atoi(argv[2]) : 16;
    const std::uint32_t samples = argc > 3 ? std::uint32_t(std::atol(argv[3])) : 0u;
    const CubeMap cube = previewReferenceCube(argv[1], 1.0, 256, LatLongPixels::Auto);
    RuntimeOptions options; // the example scene's balls: Disney diffuse, energy compensation
    options.diffuseModel = DiffuseModel::Disney;
    options.energyCompensation = true;
    std::vector<int> ball;
    const std::vector<ShadingPoint> points = materialPreviewPoints(settings.sphereSize, ball);

    ConvergedReferenceSettings effort;
    if (argc > 4) effort.brightFactor = std::atof(argv[4]);
    std::vector<int> column = ball;
    for (int& c : column)
        c %= kPreviewColumns;
    AdaptiveReferenceSettings rounds;
    if (argc > 5) rounds.firstSamples = std::uint32_t(std::atol(argv[5]));
    auto start = std::chrono::steady_clock::now();
    const AdaptiveReference adaptive = renderAdaptiveReference(cube, points, column, options, effort, rounds);
    const double adaptiveSeconds = secondsSince(start);
    std::printf("adaptive: %.2f s, samples per column:", adaptiveSeconds);
    for (std::uint32_t n : adaptive.groupSamples)
        std::printf(" %u", n);
    std::printf("\n");
    std::fflush(stdout);
    ConvergedReferenceSettings high;
    high.samples = 16384;
    high.stepsPerScale = 32.0;
    start = std::chrono::steady_clock::now();
    high.brightFactor = effort.brightFactor;
    const ConvergedReference longRun = renderConvergedReference(cube, points, options, high);
    const double longSeconds = secondsSince(start);
    std::vector<ReferenceResult> brute, bruteHalf;
    double bruteSeconds = 0.0;
    if (samples > 0) {
        const ReferenceLighting lighting = ReferenceLighting::distant(cube);
        ReferenceSettings bruteSettings;
        bruteSettings.samplesPerStrategy = samples;
        start = std::chrono::steady_clock::now();
        brute = renderReference(lighting, points, options, bruteSettings);
        bruteSeconds = secondsSince(start);
        bruteSettings.samplesPerStrategy = samples / 2;
        bruteHalf = renderReference(lighting, points, options, bruteSettings);
    }

    std::printf(
        "%s: %zu points (%d-px balls), %zu bright texels; adaptive %.2f s, long run (16384 samples, 32 "
        "steps) %.1f s, brute force (%u samples) %.1f s\n",
        argv[1], points.size(), settings.sphereSize, adaptive.reference.brightTexels, adaptiveSeconds,
        longSeconds, samples, bruteSeconds);
    std::printf("column  roughness  samples   stated  vs-long  long-own  vs-brute  brute-noise\n");
    for (int c = 0; c < kPreviewColumns; ++c) {
        double stated = 0.0, actual = 0.0, longOwn = 0.0, sum = 0.0, vsBrute = 0.0, noise = 0.0,
               bruteSum = 0.0;
        for (std::size_t k = 0; k < points.size(); ++k) {
            if (ball[k] % kPreviewColumns != c) continue;
            const double want = lum(longRun.results[k].total()),
                         got = lum(adaptive.reference.results[k].total());
            stated += lum(adaptive.reference.errorEstimate[k]);
            actual += std::abs(got - want);
            longOwn += lum(longRun.errorEstimate[k]);
            sum += want;
            if (samples > 0) {
                vsBrute += std::abs(got - lum(brute[k].total()));
                noise += std::abs(lum(bruteHalf[k].total()) - lum(brute[k].total()));
                bruteSum += lum(brute[k].total());
            }
        }
        std::printf("%6d  %9.1f  %7u  %6.3f%%  %6.3f%%  %7.3f%%  %7.3f%%  %7.3f%%\n", c, c / 10.0,
                    adaptive.groupSamples[std::size_t(c)], 100 * stated / sum, 100 * actual / sum,
                    100 * longOwn / sum, samples > 0 ? 100 * vsBrute / bruteSum : 0.0,
                    samples > 0 ? 100 * noise / bruteSum : 0.0);
    }
    return 0;
} catch (const std::exception& e) {
    std::fprintf(stderr, "reference_check: %s\n", e.what());
    return 1;
}
