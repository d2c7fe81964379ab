// The single-product commands as plans (docs/architecture.md "One stage runner"): `iblbake specular`,
// `iblbake diffuse` and `iblbake dfg` build, in memory, the plan of the stages a scene runs for their
// products (environment, sun, specular-ld; diffuse-sh, irradiance-cube; dfg-lut) with the command's settings,
// and run it through the scene's stage runner into a private cache; the products are then delivered to the
// command's files, all of them or none.
#pragma once

#include "iblbake/bake_state/bake_state.h"
#include "iblbake/baker/calibration.h"
#include "iblbake/baker/dfg_lut.h"
#include "iblbake/baker/irradiance.h"
#include "iblbake/baker/product_writers.h"
#include "iblbake/baker/sh.h"
#include "iblbake/baker/specular.h"
#include "iblbake/opencl/executor.h"
#include "iblbake/scene/scene_plan.h"

#include <nlohmann/json.hpp>

#include <filesystem>
#include <functional>
#include <map>
#include <string>
#include <vector>

namespace ibl {

// A plan and where its products go: product (as its stage names it) -> the command's file or directory.
struct ProductPlan {
    Plan plan;
    std::map<std::string, std::filesystem::path> files;
    std::string backend = "none"; // what the stages that use a backend run on (in their keys)
};

// What a run leaves for the command to print: each stage's result, and the JSON files of each stage's entry
// (stage id -> file name -> document), read before the private cache is removed.
struct ProductRun {
    std::vector<StageResult> stages;
    std::map<std::string, std::map<std::string, nlohmann::json>> facts;
    double stageSeconds(const std::string& id) const;
};

// Checks every file of `plan.files` before any work, runs the stages (the backend asked of `executor` before
// the first stage that uses one), and writes the files, all of them or none. Errors propagate as the stages
// throw them (ibl::SettingError naming the library setting, for the command to name its flag).
ProductRun runProductPlan(const ProductPlan& plan, const std::function<const Executor*()>& executor);

// The environment a command reads: its files and the settings a scene's environment stage takes, as the
// command was given them (layout and lat-long placement by name: ingest.h parseLayout, parseLatLongPixels).
struct EnvironmentJob {
    std::vector<std::filesystem::path> files;
    std::string layout = "auto";
    std::string inputColorSpace; // empty: from the file
    std::string workingColorSpace = "lin_rec709";
    float rotateDegrees = 0.0f;
    std::string latLongPixels = "auto";
    CalibrationSettings calibration;
    int faceSize = 256;
    bool extractSun = false;
    double sunMaxSolidAngle = 0.0;
    std::filesystem::path sunJson; // with extractSun: the sun's light (empty: not written)
};

// `iblbake specular`: the chain (level 0 keeping the sun's pixels when it is extracted) and its optional
// files.
struct SpecularJob {
    SpecularSettings settings;
    std::string format = "rgba16f"; // a name of ktx2.h kKtx2FormatNames
    bool clampToFormat = false;
    std::string profile = "standard";
    std::filesystem::path chain; // the KTX2 chain
    // Optional outputs (empty: none): the rough layers (KTX2 cube map array), the levels as OpenEXR, a
    // tone-mapped PNG of every level.
    std::filesystem::path roughLayers, exrDirectory, preview;
};
ProductPlan specularPlan(const EnvironmentJob& environment, const SpecularJob& job,
                         const std::string& backend);

// `iblbake diffuse`: the iblbake.diffuse document (the SH with the window asked for) and optionally the
// irradiance cube, sampled (on the backend) or evaluated from the document's SH.
struct IrradianceCubeJob {
    IrradianceMethod method = IrradianceMethod::Sampled;
    IrradianceSettings settings;
    std::string format = "rgba16f"; // a name of ktx2.h kKtx2FormatNames
    bool clampToFormat = false;
    std::string profile = "standard";
    std::filesystem::path file;
};
struct DiffuseJob {
    ShWindowSettings window;
    std::filesystem::path document;
    std::optional<IrradianceCubeJob> cube;
};
ProductPlan diffusePlan(const EnvironmentJob& environment, const DiffuseJob& job, const std::string& backend);

// `iblbake dfg`: the LUT as OpenEXR (half or float).
ProductPlan dfgPlan(const DfgSettings& settings, DfgLutFile container, const std::filesystem::path& file,
                    const std::string& backend);

// The lines a command prints of its run (docs/cli.md): its input (the environment stage's ingest report,
// the calibration, the extracted sun), the specular chain's levels and files, the SH window and the
// irradiance cube.
std::string environmentRunText(const ProductRun& run);
std::string specularRunText(const ProductPlan& plan, const ProductRun& run);
std::string diffuseRunText(const ProductPlan& plan, const ProductRun& run);

} // namespace ibl
