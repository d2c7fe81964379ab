#include "scene_stages.h"
#include "../io/ktx2_format.h"

#include "iblbake/baker/calibration.h"
#include "iblbake/baker/dfg_lut.h"
#include "iblbake/baker/environment.h"
#include "iblbake/baker/ingest.h"
#include "iblbake/baker/inspect.h"
#include "iblbake/baker/irradiance.h"
#include "iblbake/baker/light_card.h"
#include "iblbake/baker/preview.h"
#include "iblbake/baker/product_plans.h"
#include "iblbake/baker/product_writers.h"
#include "iblbake/baker/products.h"
#include "iblbake/baker/sh.h"
#include "iblbake/baker/specular.h"
#include "iblbake/baker/sun.h"
#include "iblbake/baker/sun_in_probe.h"
#include "iblbake/core/error.h"
#include "iblbake/ktx2/atomic_file.h"
#include "iblbake/ktx2/cube_profile.h"
#include "iblbake/ktx2/ktx2.h"
#include "iblbake/ktx2/output_set.h"
#include "iblbake/runtime/runtime.h"
#include "iblbake/scene/json_vec3.h"

#include <nlohmann/json.hpp>

#include <fstream>
#include <optional>

namespace ibl {

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

void writeCube(const fs::path& file, const CubeMap& cube, const std::string& product) {
    CubeMapChain chain;
    chain.levels.push_back(cube);
    writeKtx2Cube(file, chain, Ktx2Format::RGBA32F, {{"iblbake.product", product}});
}

// A calibration choice's name in stage settings: a scene's key (scene.h sceneCalibrationName).
constexpr std::pair<const char*, CalibrationSource> kCalibrationSources[] = {
    {"none", CalibrationSource::None},
    {"scale", CalibrationSource::Scale},
    {"ev100", CalibrationSource::Ev100},
    {"illuminance", CalibrationSource::Illuminance},
    {"sunIlluminance", CalibrationSource::SunIlluminance},
    {"skyLuminance", CalibrationSource::SkyLuminance},
    {"radiometric", CalibrationSource::Radiometric}};

CalibrationSettings calibrationSettings(const json& choice) {
    CalibrationSettings s;
    const std::string name = choice.at("source").get<std::string>();
    for (const auto& [key, source] : kCalibrationSources)
        if (name == key) s.source = source;
    s.value = choice.value("value", 0.0);
    return s;
}

json calibrationJson(const CalibrationRecord& record, const std::string& colorSpace) {
    return {{"factor", record.factor},
            {"absolute", record.absolute()},
            {"units", record.units()},
            {"colorSpace", colorSpace},
            {"record", calibrationRecordToJson(record)}};
}

// What an environment-like entry's calibration.json says, typed.
struct CachedCalibration {
    json document;
    CalibrationRecord record;
    std::optional<DiskLight> sun;
    std::string colorSpace() const { return document.at("colorSpace").get<std::string>(); }
    std::optional<std::string> sourceFile() const {
        if (!document.contains("source")) return std::nullopt;
        return document["source"].at("file").get<std::string>();
    }
    std::optional<LatLongPixels> latLongPixels() const {
        return document.contains("source") ? latLongPixelsFromJson(document["source"]) : std::nullopt;
    }
};

CachedCalibration readCalibration(const fs::path& entry) {
    const fs::path file = entry / kEntryFiles.calibration;
    CachedCalibration c{readJsonFile(file), {}, {}};
    try {
        if (!c.document.contains("record"))
            throw Error("no typed calibration record: an entry of an older iblbake; bake with a new --cache");
        c.record = calibrationRecordFromJson(c.document["record"]);
        if (c.document.contains("sunLight")) c.sun = diskLightFromJson(c.document["sunLight"].dump());
    } catch (const Error& e) {
        throw Error(file.string() + ": " + e.what());
    }
    return c;
}

IngestSettings ingestSettings(const json& s) {
    IngestSettings ingest;
    ingest.layout = parseLayout(s.at("layout").get<std::string>());
    ingest.inputColorSpace = s.at("colorSpace").get<std::string>();
    ingest.workingColorSpace = s.at("workingColorSpace").get<std::string>();
    ingest.rotateDegrees = s.at("rotation").get<float>();
    ingest.sourceFaceSize = s.at("faceSize").get<int>();
    ingest.latLongPixels = parseLatLongPixels(s.at("latlongPixels").get<std::string>());
    return ingest;
}

// The stage's input files, or with `keyPart` those whose scene key holds it (a probe's ".visibilityMask").
std::vector<fs::path> inputFiles(const PlanStage& stage, const std::string& keyPart = "", bool with = true) {
    std::vector<fs::path> files;
    for (const PlanInput& in : stage.inputs)
        if (keyPart.empty() || (in.keyPath.find(keyPart) != std::string::npos) == with)
            files.push_back(in.file);
    return files;
}

// The scene key that sets a library setting (SettingError::setting()) of an input stage: the environment's
// or the probe's own key ("environment.rotation", "probes[1].calibration.ev100"), the outputs' face size.
std::string sceneKeyFor(const std::string& setting, const PlanStage& stage, const std::string& inputKey) {
    const std::string owner = inputKey.substr(0, inputKey.find('.')); // "environment" or "probes[i]"
    if (setting == "layout") return owner + ".layout";
    if (setting == "inputColorSpace") return owner + ".colorSpace";
    if (setting == "workingColorSpace") return "environment.workingColorSpace";
    if (setting == "rotateDegrees") return owner + ".rotation";
    if (setting == "latLongPixels") return owner + ".latlongPixels";
    if (setting == "sourceFaceSize")
        return stage.kind == "probe-ld" ? "outputs.probeFaceSize" : "outputs.faceSize";
    if (setting == "extractSun") return "environment.extractSun";
    if (setting == "calibration") {
        const std::string source = stage.settings.at("calibration").at("source").get<std::string>();
        return source == "environment" ? "environment.calibration" : owner + ".calibration." + source;
    }
    return inputKey;
}

// Ingest errors already name the file; the scene key path in front says where the scene names it (or the
// setting that caused it).
template <class F>
void forInput(const StageContext& c, F&& work) {
    const std::string key = c.stage.inputs.empty() ? c.stage.id : c.stage.inputs[0].keyPath;
    if (c.name.empty()) return work(); // a command's plan: it names its flags itself
    try {
        work();
    } catch (const OutputError&) { // names the output and the reason: the input is not to blame
        throw;
    } catch (const SettingError& e) {
        throw Error(c.name + ": " + sceneKeyFor(e.setting(), c.stage, key) + ": " + e.what());
    } catch (const Error& e) {
        throw Error(c.name + ": " + key + ": " + e.what());
    }
}

// The environment stage's preparation: ingest and calibration; the sun stage takes the sun out.
EnvironmentSettings environmentSettings(const json& s) {
    EnvironmentSettings settings;
    settings.ingest = ingestSettings(s);
    settings.calibration = calibrationSettings(s.at("calibration"));
    return settings;
}

void runDfg(const StageContext& c) {
    DfgSettings settings;
    settings.size = c.stage.settings.at("size").get<std::uint32_t>();
    settings.sampleCount = c.stage.settings.at("samples").get<std::uint32_t>();
    // A scene's LUT is KTX2; `iblbake dfg` asks for OpenEXR ("container": "exr-float" or "exr-half").
    const std::string container = c.stage.settings.value("container", "ktx2");
    const DfgLutFile kind = container == "exr-half"    ? DfgLutFile::ExrHalf
                            : container == "exr-float" ? DfgLutFile::ExrFloat
                                                       : DfgLutFile::Ktx2;
    OutputSet outputs;
    writeDfgLutProduct(outputs, bakeDfgLut(settings, *c.executor), settings.sampleCount, kind,
                       c.outputDirectory / c.stage.products.at(0));
    outputs.commit();
}

void runEnvironment(const StageContext& c) {
    const json& s = c.stage.settings;
    forInput(c, [&] {
        const PreparedEnvironment prepared = prepareEnvironment(inputFiles(c.stage), environmentSettings(s));
        const SourceEnvironment& env = prepared.env;
        json calibration = calibrationJson(prepared.record, env.report.workingColorSpace);
        calibration["source"] = {{"file", fs::path(env.report.file).filename().string()},
                                 {"width", env.report.width},
                                 {"height", env.report.height},
                                 {"layout", layoutName(env.report.layout)},
                                 {"inputColorSpace", env.report.inputColorSpace},
                                 {"rotateDegrees", s.at("rotation")}};
        addLatLongPixels(calibration["source"], env.report.latLongPixels);
        writeCube(c.outputDirectory / kEntryFiles.cube, env.cube, "calibrated-environment");
        writeJsonFile(c.outputDirectory / kEntryFiles.calibration, calibration);
        writeJsonFile(c.outputDirectory / kEntryFiles.ingestReport,
                      {{"file", env.report.file}, {"text", ingestReportText(env.report)}});
    });
}

void runSun(const StageContext& c) {
    const fs::path from = c.dependencies.at("environment");
    CubeMap cube = readCubeFile(from / kEntryFiles.cube);
    json calibration = readJsonFile(from / kEntryFiles.calibration);
    SunDetectSettings detection;
    detection.luminanceWeights = workingLuminanceWeights(calibration.at("colorSpace").get<std::string>());
    if (c.stage.settings.contains("sunMaxSolidAngle"))
        detection.maxSolidAngle = c.stage.settings.at("sunMaxSolidAngle").get<double>();
    DiskLight light;
    try {
        light = *takeSunOut(cube, SunExtraction::Required, detection);
    } catch (const SettingError& e) {
        if (c.name.empty()) // a command's plan: the input file in front, as prepareEnvironment names it
            throw SettingError(e.setting(),
                               readJsonFile(from / kEntryFiles.ingestReport).at("file").get<std::string>() +
                                   ": " + e.what());
        throw Error(c.name + ": environment.extractSun: " + e.what());
    }
    OutputSet outputs;
    const std::string lightJson = writeSunProduct(outputs, light, calibration.at("absolute").get<bool>(),
                                                  c.outputDirectory / "sun.json");
    outputs.commit();
    calibration["sunLight"] = json::parse(lightJson);
    writeCube(c.outputDirectory / kEntryFiles.cube, cube, "calibrated-environment-without-sun");
    writeJsonFile(c.outputDirectory / kEntryFiles.calibration, calibration);
}

// What a detected sun left in the probe costs at runtime (environment.extractSun is false).
void runSunInProbe(const StageContext& c) {
    const SunInProbe check =
        measureSunInProbe(readCubeFile(c.dependencies.at("environment") / kEntryFiles.cube), *c.executor);
    json facts = {{"detected", check.detected}};
    if (check.detected)
        facts.update({{"warning", check.warning},
                      {"roughness", check.roughness},
                      {"keptError", check.keptError},
                      {"extractedError", check.extractedError}});
    writeJsonFile(c.outputDirectory / kEntryFiles.sunInProbeFacts, facts);
}

// The chain's record of what decided its texels (iblbake.settings): a scene's names its roughness range, a
// command's (settings with a "lodBias") its LOD bias, face size and rotation as given.
std::string ldSettingsText(const json& s, const SpecularSettings& settings) {
    const std::string text =
        "quality=" + s.at("quality").get<std::string>() + " samples=" + std::to_string(samplesFor(settings));
    if (!s.contains("lodBias")) return text + " roughnessMax=" + s.at("roughnessMax").dump();
    return text + " lodBias=" + std::to_string(settings.lodBias) +
           " size=" + std::to_string(s.at("faceSize").get<int>()) +
           " rotate=" + std::to_string(s.at("rotation").get<float>());
}

// Bakes and writes an LD chain (the distant environment's or a local probe's) by the product's one writer
// (product_writers.h writeLdChainProduct); returns the chain's manifest facts. With `withSun`, level 0 may
// keep the sun's pixels. With `visibility` (a local probe's capture whose alpha is not 1 everywhere), the
// chain carries it (specular.h bakeSpecularWithVisibility). With `roughLayersFile` (the distant chain when a
// material reads past r_0), the chain's rough layers too, from the same bake (specular.h
// bakeSpecularWithRoughLayers).
LdManifestFacts writeLdChain(const StageContext& c, const CubeMap& source,
                             const CachedCalibration& calibration, const std::string& product,
                             const fs::path& file, const CubeMap* withSun = nullptr, bool visibility = false,
                             const fs::path* roughLayersFile = nullptr) {
    const json& s = c.stage.settings;
    SpecularSettings settings;
    settings.mapping = parseMipMapping(s.at("mipMapping").get<std::string>());
    settings.quality = parseQuality(s.at("quality").get<std::string>());
    settings.levels = s.at("levels").get<int>();
    settings.integratedLevels = s.value("integratedLevels", 0);
    settings.samples = s.value("samples", 0u);
    settings.lodBias = s.value("lodBias", settings.lodBias);
    // `iblbake specular --profile three`: every level holds the roughness three.js reads there.
    if (s.value("levelRule", "") == kFilamentLodRuleName) {
        settings.levelRoughness = engineChainRoughness(engineProfile(s.at("profile").get<std::string>()),
                                                       settings.levels, s.at("faceSize").get<int>());
    }
    LdChainWriteSettings write;
    write.format = parseKtx2Format(s.at("ktx2Format").get<std::string>());
    if (visibility && !ktx2::formatInfo(write.format).hasAlpha)
        throw SettingError("outputs.ktx2Format", s.at("ktx2Format").get<std::string>() +
                                                     " has no alpha channel for the visibility of " +
                                                     calibration.sourceFile().value_or("the capture") +
                                                     " (use rgba16f or rgba32f)");
    SpecularWithRoughLayers baked;
    std::vector<SpecularLevelTiming> timings;
    if (visibility)
        baked.chain = bakeSpecularWithVisibility(source, settings, *c.executor).chain;
    else if (roughLayersFile)
        baked = bakeSpecularWithRoughLayers(source, settings, *c.executor, &timings);
    else
        baked.chain = bakeSpecular(source, settings, *c.executor, &timings);
    json levels = json::array();
    for (const SpecularLevelTiming& t : timings)
        levels.push_back({{"level", t.level},
                          {"perceptualRoughness", t.perceptualRoughness},
                          {"faceSize", baked.chain.levels[std::size_t(t.level)].faceSize},
                          {"milliseconds", t.milliseconds}});
    write.product.product = product;
    write.product.mapping = settings.mapping;
    write.product.levelCount = int(baked.chain.levels.size());
    write.product.levelRoughness = settings.levelRoughness;
    if (s.contains("integratedLevels")) write.product.integratedLevels = settings.integratedLevels;
    write.product.colorSpace = calibration.colorSpace();
    write.product.source = calibration.sourceFile();
    write.product.latLongPixels = calibration.latLongPixels();
    write.product.settings = ldSettingsText(s, settings);
    if (s.contains("sunMaxSolidAngle"))
        write.product.sunMaxSolidAngle = s.at("sunMaxSolidAngle").get<double>();
    write.clampToFormat = s.at("clampToFormat").get<bool>();
    write.profile = s.at("profile").get<std::string>();
    write.visibility = visibility;
    write.withSun = withSun;
    OutputSet outputs;
    const LdChainWritten written =
        writeLdChainProduct(outputs, baked, write, calibration.record, calibration.sun, file,
                            roughLayersFile ? *roughLayersFile : fs::path());
    // A command's extra views of the chain (`iblbake specular --exr, --preview`).
    if (s.value("exrLevels", false))
        writeLdChainExrLevels(outputs, baked.chain, write.product,
                              c.outputDirectory / kEntryFiles.ldExrDirectory);
    if (s.value("preview", false))
        outputs.writeFile(c.outputDirectory / kEntryFiles.ldPreview,
                          [&](const fs::path& temporary) { writeChainPreview(temporary, baked.chain); });
    outputs.commit();
    writeJsonFile(c.outputDirectory / kEntryFiles.chainReport,
                  {{"levels", levels},
                   {"clampedTexels", written.chain.stats.clampedTexels},
                   {"repairedNonFinite", written.chain.stats.repairedNonFinite}});
    writeJsonFile(c.outputDirectory / kEntryFiles.storage, productStorageToJson(written.chain.storage));
    LdManifestFacts facts;
    facts.file = file.filename().string();
    facts.format = s.at("ktx2Format").get<std::string>();
    facts.faceSize = s.at("faceSize").get<int>();
    facts.levels = s.at("levels").get<int>();
    facts.integratedLevels = settings.integratedLevels;
    facts.mapping = settings.mapping;
    facts.validRoughnessMax = s.value("roughnessMax", 1.0);
    facts.quality = s.at("quality").get<std::string>();
    if (withSun) facts.sunInLevel0 = written.sunInLevel0;
    if (written.roughLayers)
        facts.roughLayers = {roughLayersFile->filename().string(), baked.roughLayers.front().faceSize,
                             written.roughLayers->storage};
    return facts;
}

void runSpecular(const StageContext& c) {
    const fs::path from = c.dependencies.at(c.stage.dependsOn.at(0));
    const CubeMap source = readCubeFile(from / kEntryFiles.cube);
    // With the sun extracted (dependencies: sun, environment), level 0 may keep the sun's pixels.
    std::optional<CubeMap> withSun;
    if (c.stage.dependsOn.size() > 1)
        withSun = readCubeFile(c.dependencies.at("environment") / kEntryFiles.cube);
    const fs::path roughLayersFile = c.outputDirectory / kRoughLayersFile;
    LdManifestFacts facts =
        writeLdChain(c, source, readCalibration(from), "specular-ld", c.outputDirectory / "specular.ktx2",
                     withSun ? &*withSun : nullptr, false,
                     c.stage.settings.at("roughLayers").empty() ? nullptr : &roughLayersFile);
    facts.sunInLevel0 = facts.sunInLevel0.value_or(false);
    writeJsonFile(c.outputDirectory / kEntryFiles.ldManifestFacts, ldManifestFactsToJson(facts));
}

// The SH window a diffuse stage's settings name: "window" auto or a family, "windowParameter" when given.
ShWindowSettings shWindowSettings(const json& s) {
    ShWindowSettings window;
    const std::string name = s.at("window").get<std::string>();
    window.automatic = name == "auto";
    if (!window.automatic) window.window = parseShWindow(name);
    if (s.contains("windowParameter")) window.parameter = s.at("windowParameter").get<double>();
    return window;
}

void runDiffuse(const StageContext& c) {
    const fs::path from = c.dependencies.at(c.stage.dependsOn.at(0));
    const CubeMap cube = readCubeFile(from / kEntryFiles.cube);
    const CachedCalibration calibration = readCalibration(from);
    DiffuseSource source;
    if (calibration.document.contains("source")) {
        const json& in = calibration.document["source"];
        source.file = in.at("file").get<std::string>();
        source.width = in.value("width", 0);
        source.height = in.value("height", 0);
        source.layout = in.value("layout", "");
        source.inputColorSpace = in.value("inputColorSpace", "");
        source.rotateDegrees = in.value("rotateDegrees", 0.0);
        source.latLongPixels = latLongPixelsFromJson(in);
    }
    source.faceSize = cube.faceSize;
    const DiffuseSH sh = bakeDiffuseSH(cube, shWindowSettings(c.stage.settings));
    OutputSet outputs;
    writeDiffuseProduct(outputs, sh, c.stage.settings.at("window").get<std::string>(),
                        calibration.colorSpace(), source, calibration.record, calibration.sun,
                        c.outputDirectory / "diffuse.json");
    outputs.commit();
    writeJsonFile(c.outputDirectory / kEntryFiles.shReport,
                  {{"text", shWindowText(sh.window, cube.faceSize)}});
}

// The irradiance cube (E/pi), sampled from the environment on the backend, or evaluated from the SH of the
// diffuse stage it then depends on (its document's pre-scaled irradiance, read back exactly).
void runIrradiance(const StageContext& c) {
    const json& s = c.stage.settings;
    const fs::path from = c.dependencies.at(c.stage.dependsOn.at(0));
    const CachedCalibration calibration = readCalibration(from);
    const IrradianceMethod method = parseIrradianceMethod(s.at("method").get<std::string>());
    IrradianceSettings settings;
    settings.faceSize = s.at("faceSize").get<int>();
    settings.quality = parseQuality(s.at("quality").get<std::string>());
    settings.samples = s.at("samples").get<std::uint32_t>();
    settings.samples = irradianceSamplesFor(settings); // 0: the preset's (irradiance.h)
    IrradianceCubeWriteSettings write;
    write.methodText = irradianceMethodText(method, settings.samples);
    write.colorSpace = calibration.colorSpace();
    write.source = calibration.sourceFile();
    write.latLongPixels = calibration.latLongPixels();
    write.format = parseKtx2Format(s.at("ktx2Format").get<std::string>());
    write.clampToFormat = s.at("clampToFormat").get<bool>();
    write.profile = s.at("profile").get<std::string>();
    std::uint64_t shNegativeTexels = 0;
    CubeMap cube;
    if (method == IrradianceMethod::Sampled) {
        cube = bakeIrradianceCube(readCubeFile(from / kEntryFiles.cube), settings, *c.executor);
    } else {
        const json document = readJsonFile(c.dependencies.at("diffuse") / "diffuse.json");
        ShRgb irradiance;
        for (std::size_t i = 0; i < irradiance.size(); ++i)
            irradiance[i] = vec3FromJson(document.at("sh").at("irradiance").at(i));
        cube = irradianceCubeFromSH(irradiance, settings.faceSize, &shNegativeTexels);
    }
    OutputSet outputs;
    const StoredCube stored =
        writeIrradianceCubeProduct(outputs, std::move(cube), write, calibration.record, calibration.sun,
                                   c.outputDirectory / "irradiance.ktx2");
    outputs.commit();
    writeJsonFile(c.outputDirectory / kEntryFiles.storage, productStorageToJson(stored.storage));
    writeJsonFile(c.outputDirectory / kEntryFiles.irradianceReport,
                  {{"clampedTexels", stored.stats.clampedTexels}, {"shNegativeTexels", shNegativeTexels}});
}

void runProbe(const StageContext& c) {
    const json& s = c.stage.settings;
    forInput(c, [&] {
        EnvironmentSettings settings;
        settings.ingest = ingestSettings(s);
        settings.ingest.readAlpha = true; // a capture's alpha is its visibility (Frostbite 2014 4.9.1.2)
        settings.ingest.visibilityMask = inputFiles(c.stage, ".visibilityMask");
        if (s.at("calibration").at("source") == "environment") {
            const json envCalibration =
                readJsonFile(c.dependencies.at("environment") / kEntryFiles.calibration);
            settings.calibration.source = CalibrationSource::Scale;
            settings.calibration.value = envCalibration.at("factor").get<double>();
        } else {
            settings.calibration = calibrationSettings(s.at("calibration"));
        }
        const PreparedEnvironment prepared =
            prepareEnvironment(inputFiles(c.stage, ".visibilityMask", false), settings);
        const SourceEnvironment& env = prepared.env;
        json source = {{"file", fs::path(env.report.file).filename().string()}};
        addLatLongPixels(source, env.report.latLongPixels);
        const CachedCalibration calibration{
            {{"colorSpace", env.report.workingColorSpace}, {"source", source}},
            prepared.record,
            std::nullopt};
        writeLdChain(c, env.cube, calibration, "local-probe-ld", c.outputDirectory / "ld.ktx2", nullptr,
                     env.report.hasAlpha);
        ProbeVisibilityFacts facts;
        facts.visibility = env.report.hasAlpha;
        facts.alphaNanRepaired = env.report.alphaNanRepaired;
        facts.alphaNegativeRepaired = env.report.alphaNegativeRepaired;
        facts.alphaOverOneRepaired = env.report.alphaOverOneRepaired;
        writeJsonFile(c.outputDirectory / kEntryFiles.probeVisibilityFacts,
                      probeVisibilityFactsToJson(facts));
    });
}

} // namespace

json calibrationChoiceJson(const CalibrationSettings& settings) {
    for (const auto& [key, source] : kCalibrationSources)
        if (source == settings.source)
            return source == CalibrationSource::None || source == CalibrationSource::Radiometric
                       ? json{{"source", key}}
                       : json{{"source", key}, {"value", settings.value}};
    throw Error("calibration: unknown source");
}

CubeMap readCubeFile(const fs::path& file) {
    Ktx2Image image = readKtx2(file);
    if (image.faceCount != 6 || image.levels.empty()) throw Error(file.string() + ": not a cube map");
    CubeMap cube(int(image.pixelWidth));
    for (int f = 0; f < 6; ++f)
        cube.faces[f] = image.levels[0][std::size_t(f)];
    return cube;
}

void writeJsonFile(const fs::path& file, const json& doc) {
    writeFileBytes(file, doc.dump(2) + '\n');
}

json readJsonFile(const fs::path& file) {
    std::ifstream in(file);
    if (!in) throw Error(file.string() + ": cannot read");
    try {
        return json::parse(in);
    } catch (const json::exception& e) {
        throw Error(file.string() + ": " + e.what());
    }
}

std::string entryFileFor(const PlanStage& stage, const std::string& product) {
    return stage.kind == "probe-ld" ? "ld.ktx2" : product;
}

// A textured light's card (kernels/light_card.h), from its texture.
void runLightCard(const StageContext& c) {
    const json& s = c.stage.settings;
    LightCardSettings settings;
    settings.size = s.at("size").get<int>();
    settings.diffuseLayers = s.at("layers").get<int>();
    settings.format = parseKtx2Format(s.at("ktx2Format").get<std::string>());
    forInput(c, [&] {
        bakeLightCardFile(c.stage.inputs.at(0).file, c.outputDirectory / c.stage.products.at(0), settings,
                          *c.executor, s.at("workingColorSpace").get<std::string>());
    });
}

void runStage(const StageContext& c) {
    const std::string& kind = c.stage.kind;
    if (kind == "dfg-lut") return runDfg(c);
    if (kind == "environment") return runEnvironment(c);
    if (kind == "sun-extract") return runSun(c);
    if (kind == "sun-in-probe") return runSunInProbe(c);
    if (kind == "specular-ld") return runSpecular(c);
    if (kind == "diffuse-sh") return runDiffuse(c);
    if (kind == "probe-ld") return runProbe(c);
    if (kind == "irradiance-cube") return runIrradiance(c);
    if (kind == "gltf-export") return runGltfStage(c);
    if (kind == "preview-reference") return runPreviewReferenceStage(c);
    if (kind == "material-preview") return runPreviewStage(c);
    if (kind == "light-card") return runLightCard(c);
    throw Error("scene: unknown stage kind '" + kind + "'");
}

} // namespace ibl
