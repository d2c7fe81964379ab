// The flows of the single-product commands (docs/architecture.md "Where things live"): from a prepared
// environment (environment.h prepareEnvironment: ingest, calibration, sun extraction) through the bake, the
// storage and the documents to the files, all of them or none (OutputSet). `iblbake specular` and `iblbake
// diffuse` fill these jobs from their options and print what comes back; the documents are written by the
// same writers as the scene stages' (product_writers.h).
#pragma once

#include "iblbake/baker/environment.h"
#include "iblbake/baker/irradiance.h"
#include "iblbake/baker/product_writers.h"
#include "iblbake/baker/sh.h"
#include "iblbake/baker/specular.h"
#include "iblbake/opencl/executor.h"

#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace ibl {

// Called after each timed stage of a flow ("specular", "sh-projection", "irradiance-cube") with its wall
// time, e.g. to print the executor's dispatch times of that stage.
using StageTimed = std::function<void(const char* stage, double milliseconds)>;

// ---------------------------------------------------------------------------------------------------
// The LD chain of one environment, as `iblbake specular` writes it.

struct SpecularJob {
    SpecularSettings settings;
    int faceSize = 256;
    float rotateDegrees = 0.0f; // as the input was rotated: recorded in iblbake.settings
    Ktx2Format format = Ktx2Format::RGBA16F;
    bool clampToFormat = false;
    std::string profile = "standard";
    double sunMaxSolidAngle = 0.0; // recorded when level 0 keeps the sun
    std::filesystem::path chain;   // the KTX2 chain
    // Optional outputs (empty: none): the rough layers (KTX2 cube map array), the levels as OpenEXR, a
    // tone-mapped PNG of every level, the extracted sun's light.
    std::filesystem::path roughLayers, exrDirectory, preview, sunJson;
};

// Every output of the job can be written (ktx2/atomic_file.h checkOutputFile), before any work. Throws
// ibl::OutputError naming the path.
void checkSpecularOutputs(const SpecularJob& job);

struct SpecularProducts {
    std::vector<SpecularLevelTiming> timings;
    std::vector<int> levelFaceSizes;
    double bakeMilliseconds = 0.0;
    LdChainWritten written;
};

// Bakes the chain (with rough layers when job.roughLayers is set) from `input` (prepared with
// keepCubeWithSun, so that level 0 may keep the sun) and writes the job's outputs.
SpecularProducts bakeSpecularProducts(PreparedEnvironment input, const SpecularJob& job,
                                      const Executor& executor, const StageTimed& timed = {});

// ---------------------------------------------------------------------------------------------------
// The diffuse products of one environment, as `iblbake diffuse` writes them: the SH document and
// optionally an irradiance cube.

struct IrradianceCubeJob {
    IrradianceMethod method = IrradianceMethod::Sampled;
    IrradianceSettings settings;
    std::string formatName = "rgba16f"; // recorded in the document
    bool clampToFormat = false;
    std::string profile = "standard";
    std::filesystem::path file;
};

struct DiffuseJob {
    ShWindowSettings window;
    std::string requestedWindow = "auto"; // as the user named it
    float rotateDegrees = 0.0f;
    std::optional<IrradianceCubeJob> cube;
    std::filesystem::path document;  // the iblbake.diffuse JSON
    std::filesystem::path sunJson;   // empty: none
    double ingestMilliseconds = 0.0; // recorded in the document's "timing"
};

void checkDiffuseOutputs(const DiffuseJob& job);

struct DiffuseProducts {
    DiffuseSH sh;
    double shMilliseconds = 0.0, cubeMilliseconds = 0.0;
    std::optional<StoredCube> cube;
    std::uint64_t shNegativeTexels = 0; // of a cube evaluated from the SH, clamped to 0
};

// The SH window's report (`iblbake diffuse`): the window chosen, and the smallest irradiance before and
// after it, per channel and as the worst channel's percentage of its mean; two lines.
std::string shWindowText(const ShWindowResult& window, int faceSize);

// `executor` runs the sampled irradiance cube (the SH are projected on the CPU).
DiffuseProducts bakeDiffuseProducts(const PreparedEnvironment& input, const DiffuseJob& job,
                                    const Executor& executor, const StageTimed& timed = {});

} // namespace ibl
