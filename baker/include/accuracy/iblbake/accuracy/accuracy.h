// The accuracy sweep behind `iblbake accuracy` (docs/accuracy.md "What accuracy costs in time"): the quality
// knobs of every stage swept on one environment, each setting timed (median of repeats) and compared with the
// stage's brute-force reference at sizes where that is affordable, and the reports of a run: report.json
// (schema iblbake.accuracy), report.md (docs/accuracy.md "The sample's report") and report.html (one SVG plot
// per stage).
#pragma once

#include "iblbake/core/cubemap.h"
#include "iblbake/opencl/executor.h"

#include <chrono>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace ibl {

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
    // The reference's own estimated error per part, in the stage's error measure (converged references).
    std::vector<std::pair<std::string, double>> referenceErrors;
    std::vector<std::string> warnings; // one line each (sunInProbeWarning)
};

struct AccuracyRun {
    std::string input;
    int sourceFaceSize = 0;
    int productionFaceSize = 0; // of the specular-production, SH, irradiance and runtime stages
    bool quick = false;
    int repeats = 0;
    std::string backend;
    std::string load; // /proc/loadavg at the start and the end
    unsigned hardwareThreads = 0;
    double totalSeconds = 0.0;
    std::vector<AccuracyStage> stages;
};

struct SweepPlan {
    int sourceFaceSize = 64; // source cube of the specular sweep's largest size
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
    // The size bakes ship (iblbake specular's default --size): the LD chain at each preset (and these sample
    // counts) against referenceSpecularTexels at productionTexelsPerLevel texels of every level (all of a
    // smaller level); the SH, the irradiance cube and the runtime from a source of this size.
    int productionFaceSize = 256;
    int productionTexelsPerLevel = 1536;
    std::vector<std::uint32_t> productionSamples{};
    // Irradiance cube (and the SH's irradiance) at this face size, from the productionFaceSize source.
    int irradianceFaceSize = 32;
    std::vector<std::uint32_t> irradianceSamples{32, 64, 128, 256, 512, 1024, 2048, 4096};
    // Runtime: sphere grids of these perceptual roughnesses (grid x grid pixels per camera, two cameras),
    // against renderConvergedReference.
    std::vector<float> runtimeRoughness{0.0f, 0.1f, 0.2f, 0.3f, 0.4f, 0.5f, 0.6f, 0.7f, 0.8f, 0.9f, 1.0f};
    int runtimeGrid = 7;
    bool isQuick = false; // quick(): the reports say "quick sweep"

    static SweepPlan full() { return {}; }
    static SweepPlan quick(); // seconds: what the tests run
};

// Reads the input at a face size (the caller's ingest settings).
using CubeLoader = std::function<CubeMap(int faceSize)>;

struct AccuracyInput {
    std::string name; // as the reports name it (the file name)
    CubeMap source;   // at the plan's sourceFaceSize
    CubeLoader load;  // at the other face sizes the plan sweeps
};

// Every stage of the plan measured, in report order (dfg, specular, specular-production, sh, irradiance,
// runtime); `stageMeasured` (optional) sees each stage as soon as it is measured. totalSeconds counts from
// `start` (the caller's start, so that reading the input counts).
AccuracyRun runAccuracySweep(const SweepPlan& plan, const AccuracyInput& input, int repeats,
                             const Executor& executor,
                             const std::function<void(const AccuracyStage&)>& stageMeasured = {},
                             std::chrono::steady_clock::time_point start = std::chrono::steady_clock::now());

std::string accuracyJson(const AccuracyRun& run);
std::string accuracyMarkdown(const AccuracyRun& run);
std::string accuracyHtml(const AccuracyRun& run);

// Writes report.json, report.md and report.html into `directory` (created with its parents) all three or
// none (OutputSet): into a temporary sibling renamed to `directory`, or, when it exists, each report by a
// rename of its own (its other files stay). Throws ibl::OutputError when a report cannot be written.
void writeAccuracyReports(const std::filesystem::path& directory, const AccuracyRun& run);

} // namespace ibl
