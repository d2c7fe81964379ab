// The single-product commands' plans and their run (iblbake/baker/product_plans.h).
#include "iblbake/baker/product_plans.h"

#include "iblbake/core/error.h"
#include "iblbake/ktx2/atomic_file.h"
#include "iblbake/ktx2/cube_profile.h"
#include "iblbake/ktx2/dds.h"
#include "iblbake/ktx2/output_set.h"
#include "scene_stages.h"
#include "stage_cache.h"
#include "stage_keys.h"
#include "stage_runner.h"

namespace ibl {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

// The private cache of one run: a new directory under the system's temporary directory, removed with
// everything in it when the run ends (its entries are never reused).
class PrivateCache {
  public:
    PrivateCache() : directory_(fs::temp_directory_path() / ("iblbake-" + uniqueSuffix())) {}
    PrivateCache(const PrivateCache&) = delete;
    PrivateCache& operator=(const PrivateCache&) = delete;
    ~PrivateCache() {
        std::error_code ignored;
        fs::remove_all(directory_, ignored);
    }
    const fs::path& directory() const { return directory_; }

  private:
    fs::path directory_;
};

// Every file the plan delivers, checked before any work (a directory output: its first file): where it can be
// written, and named for the container its product is (specular.ktx2: KTX2; the cube products KTX2 or DDS).
void checkDeliveries(const ProductPlan& plan) {
    std::map<fs::path, std::string> productOf;
    for (const auto& [product, file] : plan.files)
        if (const auto [at, added] = productOf.emplace(fs::absolute(file).lexically_normal(), product);
            !added)
            throw Error(file.string() + ": given for two products, " + at->second + " and " + product);
    for (const auto& [product, file] : plan.files) {
        if (product == "specular.ktx2" || product == kRoughLayersFile || product == "irradiance.ktx2") {
            checkOutputFile(file);
            checkCubeOutputExtension(file);
        } else if (product != kEntryFiles.ldExrDirectory) {
            checkOutputFile(file);
            checkOutputExtension(file, fs::path(product).extension().string());
        } else if (fs::exists(file) && !fs::is_directory(file)) {
            throw Error(file.string() + ": is not a directory (--exr)");
        } else {
            checkOutputFile(fs::is_directory(file) ? file / "level_0.exr" : file);
        }
    }
}

// The stage that makes `product`.
const PlanStage& stageOf(const Plan& plan, const std::string& product) {
    for (const PlanStage& s : plan.stages)
        for (const std::string& p : s.products)
            if (p == product) return s;
    throw Error("plan: no stage makes " + product);
}

// Every JSON file of an entry, by name.
std::map<std::string, json> entryFacts(const fs::path& entry) {
    std::map<std::string, json> facts;
    for (const fs::directory_entry& file : fs::directory_iterator(entry))
        if (file.path().extension() == ".json" && file.path().filename() != "entry.json")
            facts[file.path().filename().string()] = readJsonFile(file.path());
    return facts;
}

// A plan that starts with the environment stage of a command's input (the scene's "environment" kind) and its
// sun stage.
ProductPlan environmentPlan(const EnvironmentJob& e, const std::string& backend) {
    ProductPlan p;
    p.backend = backend;
    Plan& plan = p.plan;
    PlanStage environment{"environment", "environment", {}, {}, {}, {}, false, "ingest and calibrate"};
    for (std::size_t i = 0; i < e.files.size(); ++i)
        environment.inputs.push_back({"input[" + std::to_string(i) + "]", e.files[i]});
    environment.settings = {{"layout", e.layout},
                            {"colorSpace", e.inputColorSpace},
                            {"workingColorSpace", e.workingColorSpace},
                            {"rotation", e.rotateDegrees},
                            {"latlongPixels", e.latLongPixels},
                            {"calibration", calibrationChoiceJson(e.calibration)},
                            {"faceSize", e.faceSize}};
    plan.stages.push_back(std::move(environment));
    if (!e.extractSun) return p;
    PlanStage sun{
        "sun",        "sun-extract", {"environment"},          {}, {{"sunMaxSolidAngle", e.sunMaxSolidAngle}},
        {"sun.json"}, false,         "the sun as a disk light"};
    plan.stages.push_back(std::move(sun));
    if (!e.sunJson.empty()) p.files["sun.json"] = e.sunJson;
    return p;
}

} // namespace

double ProductRun::stageSeconds(const std::string& id) const {
    for (const StageResult& s : stages)
        if (s.id == id) return s.seconds;
    return 0.0;
}

ProductRun runProductPlan(const ProductPlan& plan, const std::function<const Executor*()>& executor) {
    checkDeliveries(plan);
    ProductRun out;
    // The keys only name the private cache's entries, which no later run finds: the inputs' content is left
    // out of them (reading a large HDRI twice would cost as much as its ingest).
    std::map<std::string, std::string> inputHashes;
    for (const PlanStage& s : plan.plan.stages)
        for (const PlanInput& in : s.inputs)
            inputHashes[in.file.string()] = "";
    const std::map<std::string, std::string> keys = planStageKeys(plan.plan, inputHashes, plan.backend);
    for (const PlanStage& s : plan.plan.stages)
        out.stages.push_back({s.id, s.kind, StageStatus::Pending, keys.at(s.id), 0.0, s.products});

    const PrivateCache privateCache;
    const StageCache cache(privateCache.directory());
    ProgressSink quiet;
    std::size_t current = 0;
    const StageRun run = runStages({"", cache, executor, true, quiet}, plan.plan, out.stages, current);
    OutputSet outputs; // all of them or none
    for (const auto& [product, file] : plan.files) {
        const fs::path from = run.entries.at(stageOf(plan.plan, product).id) / product;
        if (fs::is_directory(from)) {
            outputs.writeDirectory(file, [&](const fs::path& temporary) {
                for (const fs::directory_entry& f : fs::directory_iterator(from))
                    copyProductFile(f.path(), temporary / f.path().filename());
            });
        } else if (lowercaseExtension(file) == ".dds") { // a cube product's KTX2, rewrapped
            outputs.writeFile(file, [&](const fs::path& temporary) { writeDdsFromKtx2(from, temporary); });
        } else {
            outputs.writeFile(file, [&](const fs::path& temporary) { copyProductFile(from, temporary); });
        }
    }
    outputs.commit();
    for (const PlanStage& s : plan.plan.stages)
        out.facts[s.id] = entryFacts(run.entries.at(s.id));
    return out;
}

ProductPlan specularPlan(const EnvironmentJob& environment, const SpecularJob& job,
                         const std::string& backend) {
    ProductPlan p = environmentPlan(environment, backend);
    const SpecularSettings& s = job.settings;
    PlanStage specular{"specular",
                       "specular-ld",
                       {environment.extractSun ? "sun" : "environment"},
                       {},
                       {},
                       {"specular.ktx2"},
                       true,
                       "the LD chain"};
    // Level 0 keeps the sun's pixels where the format holds them: the cube from before the extraction too.
    if (environment.extractSun) specular.dependsOn.push_back("environment");
    // An engine profile with its own level rule (three: FilamentLod) fixes the chain's length and roughness.
    const EngineProfile& engine = engineProfile(job.profile);
    if (engine.levelRule != LevelRule::Baked && s.levels > 0)
        throw SettingError("levels", "the " + job.profile + " profile's chain runs down to " +
                                         std::to_string(engine.smallestFace) +
                                         "-px faces; leave --levels out");
    specular.settings = {
        {"faceSize", environment.faceSize},
        {"levels", engine.levelRule == LevelRule::Baked ? levelCountFor(environment.faceSize, s)
                                                        : engineLevelCount(engine, environment.faceSize)},
        {"mipMapping", mipMappingName(s.mapping)},
        {"quality", qualityName(s.quality)},
        {"samples", s.samples},
        {"lodBias", s.lodBias},
        {"rotation", environment.rotateDegrees},
        {"ktx2Format", job.format},
        {"clampToFormat", job.clampToFormat},
        {"profile", job.profile},
        {"sunMaxSolidAngle", environment.sunMaxSolidAngle},
        {"roughLayers", job.roughLayers.empty() ? json::array() : json(roughLayerRoughnessValues())},
        {"exrLevels", !job.exrDirectory.empty()},
        {"preview", !job.preview.empty()}};
    if (engine.levelRule == LevelRule::FilamentLod) {
        specular.settings["levelRule"] = kFilamentLodRuleName;
        specular.settings["mipMapping"] = kFilamentLodMappingName;
    }
    p.files["specular.ktx2"] = job.chain;
    if (!job.roughLayers.empty()) {
        specular.products.push_back(kRoughLayersFile);
        p.files[kRoughLayersFile] = job.roughLayers;
    }
    if (!job.exrDirectory.empty()) {
        specular.products.push_back(kEntryFiles.ldExrDirectory);
        p.files[kEntryFiles.ldExrDirectory] = job.exrDirectory;
    }
    if (!job.preview.empty()) {
        specular.products.push_back(kEntryFiles.ldPreview);
        p.files[kEntryFiles.ldPreview] = job.preview;
    }
    p.plan.stages.push_back(std::move(specular));
    return p;
}

ProductPlan diffusePlan(const EnvironmentJob& environment, const DiffuseJob& job,
                        const std::string& backend) {
    ProductPlan p = environmentPlan(environment, backend);
    const std::string lightSource = environment.extractSun ? "sun" : "environment";
    const ShWindowSettings& w = job.window;
    PlanStage diffuse{"diffuse", "diffuse-sh", {lightSource}, {}, {}, {"diffuse.json"}, false, "the SH"};
    if (w.parameter && (w.automatic || w.window == ShWindow::None))
        throw SettingError("windowParameter", "needs a window: sloan, hanning or lanczos");
    diffuse.settings = {{"window", w.automatic ? "auto" : shWindowName(w.window)}};
    if (w.parameter) diffuse.settings["windowParameter"] = *w.parameter;
    p.plan.stages.push_back(std::move(diffuse));
    p.files["diffuse.json"] = job.document;
    if (!job.cube) return p;
    const IrradianceCubeJob& c = *job.cube;
    const bool sampled = c.method == IrradianceMethod::Sampled;
    if (sampled && (environment.faceSize & (environment.faceSize - 1)) != 0)
        throw SettingError("sourceFaceSize",
                           std::to_string(environment.faceSize) +
                               " is not a power of two (the sampled irradiance cube needs one)");
    PlanStage cube{"irradiance", "irradiance-cube",   {lightSource}, {},
                   {},           {"irradiance.ktx2"}, sampled,       "the irradiance cube"};
    if (!sampled) cube.dependsOn.push_back("diffuse"); // evaluated from its SH
    cube.settings = {{"method", irradianceMethodName(c.method)},
                     {"faceSize", c.settings.faceSize},
                     {"quality", qualityName(c.settings.quality)},
                     {"samples", c.settings.samples},
                     {"ktx2Format", c.format},
                     {"clampToFormat", c.clampToFormat},
                     {"profile", c.profile}};
    p.plan.stages.push_back(std::move(cube));
    p.files["irradiance.ktx2"] = c.file;
    return p;
}

ProductPlan dfgPlan(const DfgSettings& settings, DfgLutFile container, const fs::path& file,
                    const std::string& backend) {
    ProductPlan p;
    p.backend = backend;
    PlanStage dfg{"dfg", "dfg-lut", {}, {}, {}, {"dfg_lut.exr"}, true, "the DFG LUT"};
    dfg.settings = {{"size", settings.size},
                    {"samples", settings.sampleCount},
                    {"container", container == DfgLutFile::ExrHalf ? "exr-half" : "exr-float"}};
    p.plan.stages.push_back(std::move(dfg));
    p.files["dfg_lut.exr"] = file;
    return p;
}

} // namespace ibl
