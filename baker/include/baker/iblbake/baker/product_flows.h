// The flow of `iblbake diffuse` (docs/architecture.md "Where things live"): from a prepared environment
// (environment.h prepareEnvironment: ingest, calibration, sun extraction) through the bake, the storage and
// the documents to the files, all of them or none (OutputSet), by the same writers as the scene stages'
// (product_writers.h). `iblbake specular` and `iblbake dfg` run plans of the scene's stages instead
// (product_plans.h).
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

// `iblbake diffuse`'s report of its products: the SH window (shWindowText, from `sourceFaceSize` px faces),
// the irradiance cube and its storage when written, the files.
std::string diffuseProductsText(const DiffuseJob& job, const DiffuseProducts& products, int sourceFaceSize);

// `executor` runs the sampled irradiance cube (the SH are projected on the CPU).
DiffuseProducts bakeDiffuseProducts(const PreparedEnvironment& input, const DiffuseJob& job,
                                    const Executor& executor, const StageTimed& timed = {});

} // namespace ibl
