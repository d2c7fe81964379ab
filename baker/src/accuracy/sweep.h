// `iblbake accuracy`: the quality knobs of every stage swept on one environment, each setting timed (median
// of repeats) and compared with the stage's brute-force reference at sizes where that is affordable.
#pragma once

#include "model.h"

#include <iblbake/cubemap.h>
#include <iblbake/executor.h>

#include <cstdint>
#include <functional>
#include <vector>

namespace ibl::cli {

struct SweepPlan {
    int sourceFaceSize = 64; // source cube of the specular (largest size), SH, irradiance and runtime sweeps
    // DFG: LUTs of every size x samples, read bilinearly (as the runtime does) at the centres of a
    // referenceSize^2 grid integrated in fp64 with referenceSamples samples. The grid size is odd so that
    // its points fall between the texel centres of every power-of-two LUT (an even grid would coincide with
    // one LUT size's texels and spare it the interpolation error the others pay). 2^16 samples: the
    // reference's own noise is then ~1e-3 at grazing NoV (tests/test_dfg.cpp), the floor of "max error".
    std::uint32_t dfgReferenceSize = 33, dfgReferenceSamples = 1u << 16;
    std::vector<std::uint32_t> dfgSizes{16, 32, 64, 128}, dfgSamples{64, 256, 1024, 4096};
    // Specular: face sizes (ingested from the input at each) x max samples per texel x source-LOD bias.
    std::vector<int> specularSizes{32, 64};
    std::vector<std::uint32_t> specularSamples{16, 32, 64, 128, 256, 512, 1024, 2048};
    std::vector<float> specularBiases{-1.0f, -0.5f, 0.0f, 0.5f};
    // Specular at the size bakes ship (iblbake specular's default --size), where the brute force is not
    // affordable: against the same chain at convergedSamples (self-convergence, stated as such).
    int convergenceFaceSize = 256;
    std::uint32_t convergedSamples = 8192;
    std::vector<std::uint32_t> convergenceSamples{32, 64, 128, 256, 512, 1024, 2048};
    // Irradiance cube (and the SH's irradiance) at this face size.
    int irradianceFaceSize = 32;
    std::vector<std::uint32_t> irradianceSamples{32, 64, 128, 256, 512, 1024, 2048, 4096};
    // Runtime: sphere grids of these perceptual roughnesses (grid x grid pixels per camera, two cameras),
    // against renderReference with this many samples per strategy.
    std::vector<float> runtimeRoughness{0.0f, 0.1f, 0.2f, 0.3f, 0.4f, 0.5f, 0.6f, 0.7f, 0.8f, 0.9f, 1.0f};
    int runtimeGrid = 7;
    std::uint32_t runtimeReferenceSamples = 256;

    static SweepPlan full() { return {}; }
    static SweepPlan quick(); // seconds: what the tests run
};

// Reads the input at a face size (the command's ingest settings).
using CubeLoader = std::function<CubeMap(int faceSize)>;

AccuracyStage measureDfg(const SweepPlan& plan, int repeats, const Executor& executor);
AccuracyStage measureSpecular(const SweepPlan& plan, const CubeLoader& load, int repeats,
                              const Executor& executor);
AccuracyStage measureSpecularConvergence(const SweepPlan& plan, const CubeLoader& load, int repeats,
                                         const Executor& executor);
// The SH and the irradiance cube share their reference (referenceIrradianceCube).
std::vector<AccuracyStage> measureDiffuse(const SweepPlan& plan, const CubeMap& source, int repeats,
                                          const Executor& executor);
AccuracyStage measureRuntime(const SweepPlan& plan, const CubeMap& source, int repeats,
                             const Executor& executor);

// Runs `work` `repeats` times and returns each run's wall time in milliseconds.
std::vector<double> timeRuns(int repeats, const std::function<void()>& work);
double median(std::vector<double> values);

} // namespace ibl::cli
