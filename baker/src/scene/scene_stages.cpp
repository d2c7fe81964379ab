#include "scene_stages.h"

#include "iblbake/calibration.h"
#include "iblbake/dfg_lut.h"
#include "iblbake/environment.h"
#include "iblbake/error.h"
#include "iblbake/ingest.h"
#include "iblbake/irradiance.h"
#include "iblbake/ktx2.h"
#include "iblbake/sh.h"
#include "iblbake/specular.h"
#include "iblbake/sun.h"

#include <nlohmann/json.hpp>

#include <fstream>
#include <optional>

namespace ibl {

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

void writeJson(const fs::path& file, const json& doc) {
    std::ofstream out(file);
    out << doc.dump(2) << '\n';
    out.close();
    if (!out) throw Error(file.string() + ": cannot write");
}

CubeMap readCube(const fs::path& file) {
    Ktx2Image image = readKtx2(file);
    if (image.faceCount != 6 || image.levels.empty()) throw Error(file.string() + ": not a cube map");
    CubeMap cube(int(image.pixelWidth));
    for (int f = 0; f < 6; ++f)
        cube.faces[f] = image.levels[0][std::size_t(f)];
    return cube;
}

void writeCube(const fs::path& file, const CubeMap& cube, const std::string& product) {
    CubeMapChain chain;
    chain.levels.push_back(cube);
    writeKtx2Cube(file, chain, Ktx2Format::RGBA32F, {{"iblbake.product", product}});
}

Ktx2Format ktx2Format(const std::string& name) {
    if (name == "rgba32f") return Ktx2Format::RGBA32F;
    if (name == "b10g11r11") return Ktx2Format::B10G11R11;
    if (name == "e5b9g9r9") return Ktx2Format::E5B9G9R9;
    return Ktx2Format::RGBA16F;
}

CalibrationSettings calibrationSettings(const json& choice) {
    static const std::map<std::string, CalibrationSource> sources = {
        {"none", CalibrationSource::None},
        {"scale", CalibrationSource::Scale},
        {"ev100", CalibrationSource::Ev100},
        {"illuminance", CalibrationSource::Illuminance},
        {"sunIlluminance", CalibrationSource::SunIlluminance},
        {"skyLuminance", CalibrationSource::SkyLuminance},
        {"radiometric", CalibrationSource::Radiometric}};
    CalibrationSettings s;
    s.source = sources.at(choice.at("source").get<std::string>());
    s.value = choice.value("value", 0.0);
    return s;
}

json calibrationJson(const CalibrationRecord& record, const std::string& colorSpace) {
    json metadata = json::object();
    for (const auto& [key, value] : calibrationMetadata(record, ""))
        metadata[key] = value;
    return {{"factor", record.factor},
            {"absolute", record.absolute()},
            {"units", record.absolute() ? "cd/m2" : "relative"},
            {"colorSpace", colorSpace},
            {"metadata", metadata}};
}

// The calibration (and sun) key/values every KTX2 product carries, as the CLI's outputs do.
Ktx2KeyValues calibrationKeyValues(const json& calibration) {
    Ktx2KeyValues kv;
    for (const auto& [key, value] : calibration.at("metadata").items())
        kv.emplace_back("iblbake." + key, value.get<std::string>());
    if (calibration.contains("sunLight")) {
        kv.emplace_back("iblbake.sun", "extracted as a disk light (Frostbite 4.6), see iblbake.sunLight");
        kv.emplace_back("iblbake.sunLight", calibration["sunLight"].dump());
    } else {
        kv.emplace_back("iblbake.sun", "kept in the environment");
    }
    return kv;
}

IngestSettings ingestSettings(const json& s) {
    IngestSettings ingest;
    ingest.layout = parseLayout(s.at("layout").get<std::string>());
    ingest.inputColorSpace = s.at("colorSpace").get<std::string>();
    ingest.workingColorSpace = s.at("workingColorSpace").get<std::string>();
    ingest.rotateDegrees = s.at("rotation").get<float>();
    ingest.sourceFaceSize = s.at("faceSize").get<int>();
    return ingest;
}

std::vector<fs::path> inputFiles(const PlanStage& stage) {
    std::vector<fs::path> files;
    for (const PlanInput& in : stage.inputs)
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
    try {
        work();
    } catch (const SettingError& e) {
        throw Error(c.scene.name + ": " + sceneKeyFor(e.setting(), c.stage, key) + ": " + e.what());
    } catch (const Error& e) {
        throw Error(c.scene.name + ": " + key + ": " + e.what());
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
    ImageRGBA lut = bakeDfgLut(settings, *c.executor);
    writeKtx2Image(
        c.outputDirectory / "dfg_lut.ktx2", lut, Ktx2Format::RGBA32F,
        {{"iblbake.product", "dfg-lut"},
         {"iblbake.layout",
          "x: NoV=(x+0.5)/N; y: perceptualRoughness=(y+0.5)/N from the first row; R=DFG1=E[(1-Fc)GVis] "
          "G=DFG2=E[Fc GVis] (Frostbite Listing 18, height-correlated Smith GGX); B=renormalized "
          "Disney diffuse (Frostbite Listing 1)"},
         {"iblbake.samples", std::to_string(settings.sampleCount)}});
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
        writeCube(c.outputDirectory / kCubeFile, env.cube, "calibrated-environment");
        writeJson(c.outputDirectory / kCalibrationFile, calibration);
    });
}

void runSun(const StageContext& c) {
    const fs::path from = c.dependencies.at("environment");
    CubeMap cube = readCube(from / kCubeFile);
    json calibration = readJsonFile(from / kCalibrationFile);
    SunDetectSettings detection;
    detection.luminanceWeights = workingLuminanceWeights(calibration.at("colorSpace").get<std::string>());
    DiskLight light;
    try {
        light = *takeSunOut(cube, SunExtraction::Required, detection);
    } catch (const SettingError& e) {
        throw Error(c.scene.name + ": environment.extractSun: " + e.what());
    }
    const bool absolute = calibration.at("absolute").get<bool>();
    calibration["sunLight"] = json::parse(diskLightToJson(light, absolute));
    writeCube(c.outputDirectory / kCubeFile, cube, "calibrated-environment-without-sun");
    writeJson(c.outputDirectory / kCalibrationFile, calibration);
    std::ofstream out(c.outputDirectory / "sun.json");
    out << diskLightToJson(light, absolute) << '\n';
    out.close();
    if (!out) throw Error((c.outputDirectory / "sun.json").string() + ": cannot write");
}

std::string mappingText(MipMapping mapping) {
    return std::string(mipMappingName(mapping)) +
           (mapping == MipMapping::Frostbite ? ": level m of L holds perceptualRoughness (m/(L-1))^2"
                                             : ": level m of L holds perceptualRoughness m/(L-1)");
}

// Bakes and writes an LD chain (the distant environment's or a local probe's).
// Returns whether level 0 kept the sun's pixels (only with `withSun`).
bool writeLdChain(const StageContext& c, const CubeMap& source, const json& calibration,
                  const std::string& product, const fs::path& file, const CubeMap* withSun = nullptr) {
    const json& s = c.stage.settings;
    SpecularSettings settings;
    settings.mapping = parseMipMapping(s.at("mipMapping").get<std::string>());
    settings.quality = parseQuality(s.at("quality").get<std::string>());
    settings.integratedLevels = s.at("integratedLevels").get<int>();
    CubeMapChain chain = bakeSpecular(source, settings, *c.executor);
    Ktx2KeyValues kv = {{"iblbake.product", product},
                        {"iblbake.roughnessMapping", mappingText(settings.mapping)},
                        {"iblbake.levelCount", std::to_string(chain.levels.size())},
                        {"iblbake.integratedLevels", std::to_string(settings.integratedLevels)},
                        {"iblbake.colorSpace", calibration.at("colorSpace").get<std::string>()},
                        {"iblbake.settings", "quality=" + s.at("quality").get<std::string>() +
                                                 " samples=" + std::to_string(samplesFor(settings)) +
                                                 " roughnessMax=" + s.at("roughnessMax").dump()}};
    if (calibration.contains("source"))
        kv.emplace_back("iblbake.source", calibration["source"].at("file").get<std::string>());
    for (auto& entry : calibrationKeyValues(calibration))
        kv.push_back(entry);
    const Ktx2Format format = ktx2Format(s.at("ktx2Format").get<std::string>());
    const bool sunInLevel0 = withSun && keepSunInLevel0(chain, *withSun, format);
    if (sunInLevel0) kv.emplace_back("iblbake.sunInLevel0", "true");
    writeKtx2Cube(file, chain, format, kv);
    return sunInLevel0;
}

void runSpecular(const StageContext& c) {
    const fs::path from = c.dependencies.at(c.stage.dependsOn.at(0));
    const CubeMap source = readCube(from / kCubeFile);
    // With the sun extracted (dependencies: sun, environment), level 0 may keep the sun's pixels.
    std::optional<CubeMap> withSun;
    if (c.stage.dependsOn.size() > 1) withSun = readCube(c.dependencies.at("environment") / kCubeFile);
    const bool sunInLevel0 = writeLdChain(c, source, readJsonFile(from / kCalibrationFile), "specular-ld",
                                          c.outputDirectory / "specular.ktx2", withSun ? &*withSun : nullptr);
    writeJson(c.outputDirectory / kLdFacts, {{"sunInLevel0", sunInLevel0}});
}

json rgb(const glm::dvec3& v) {
    return json::array({v.x, v.y, v.z});
}

json coefficients(const ShRgb& sh) {
    json a = json::array();
    for (const glm::dvec3& v : sh)
        a.push_back(rgb(v));
    return a;
}

void runDiffuse(const StageContext& c) {
    const fs::path from = c.dependencies.at(c.stage.dependsOn.at(0));
    const CubeMap cube = readCube(from / kCubeFile);
    json calibration = readJsonFile(from / kCalibrationFile);
    const DiffuseSH sh = bakeDiffuseSH(cube, ShWindowSettings{});
    const ShWindowResult& w = sh.window;
    json doc = {
        {"schema", "iblbake.diffuse"},
        {"schemaVersion", 1},
        {"generator", "iblbake " IBLBAKE_VERSION},
        {"colorSpace", calibration.at("colorSpace")},
        {"units", calibration.at("absolute").get<bool>() ? "cd/m2 (luminance); irradiance in lux"
                                                         : "relative (input values, uncalibrated)"},
        {"calibration", calibration.at("metadata")},
        {"sh",
         {{"order", 2},
          {"basis", "real spherical harmonics, standard (orthonormal) normalization, DESIGN.md order"},
          {"window",
           {{"name", shWindowName(w.window)},
            {"parameter", w.parameter},
            {"searched", w.searched},
            {"bandFactors", {w.factors[0], w.factors[1], w.factors[2]}}}},
          {"radiance", coefficients(sh.radiance)},
          {"irradiance", coefficients(sh.irradiance)},
          {"irradianceConvention", "c_i = A_l k_i L_i: Filament's irradianceSH(n) returns E(n)"},
          {"irradianceOverPi", coefficients(sh.irradianceOverPi)}}}};
    if (calibration.contains("sunLight")) doc["calibration"]["sunLight"] = calibration["sunLight"];
    writeJson(c.outputDirectory / "diffuse.json", doc);
}

// The same cube and key/values as `iblbake diffuse --irradiance-cube` (cli/diffuse_command.cpp).
void runIrradiance(const StageContext& c) {
    const json& s = c.stage.settings;
    const fs::path from = c.dependencies.at(c.stage.dependsOn.at(0));
    const json calibration = readJsonFile(from / kCalibrationFile);
    IrradianceSettings settings;
    settings.faceSize = s.at("faceSize").get<int>();
    settings.quality = parseQuality(s.at("quality").get<std::string>());
    settings.samples = irradianceSamplesFor(settings); // the preset's (irradiance.h)
    CubeMapChain chain;
    chain.levels.push_back(bakeIrradianceCube(readCube(from / kCubeFile), settings, *c.executor));
    Ktx2KeyValues kv = {
        {"iblbake.product", "irradiance"},
        {"iblbake.irradianceNormalization",
         "E/pi: each texel stores (1/pi) integral L(l) max(0,n.l) dl, the cosine-weighted mean radiance "
         "(Frostbite Listing 20's LD of a Lambert lobe); irradiance E = pi x value"},
        {"iblbake.method",
         "sampled: cosine importance sampling, " + std::to_string(settings.samples) +
             " samples/texel, pre-filtered lookups (Frostbite Listing 20 + Listing 19 LOD), "
             "bright texels integrated exactly"},
        {"iblbake.colorSpace", calibration.at("colorSpace").get<std::string>()}};
    if (calibration.contains("source"))
        kv.emplace_back("iblbake.source", calibration["source"].at("file").get<std::string>());
    for (auto& entry : calibrationKeyValues(calibration))
        kv.push_back(entry);
    writeKtx2Cube(c.outputDirectory / "irradiance.ktx2", chain,
                  ktx2Format(s.at("ktx2Format").get<std::string>()), kv);
}

void runProbe(const StageContext& c) {
    const json& s = c.stage.settings;
    forInput(c, [&] {
        EnvironmentSettings settings;
        settings.ingest = ingestSettings(s);
        if (s.at("calibration").at("source") == "environment") {
            const json envCalibration = readJsonFile(c.dependencies.at("environment") / kCalibrationFile);
            settings.calibration.source = CalibrationSource::Scale;
            settings.calibration.value = envCalibration.at("factor").get<double>();
        } else {
            settings.calibration = calibrationSettings(s.at("calibration"));
        }
        const PreparedEnvironment prepared = prepareEnvironment(inputFiles(c.stage), settings);
        const SourceEnvironment& env = prepared.env;
        json calibration = calibrationJson(prepared.record, env.report.workingColorSpace);
        calibration["source"] = {{"file", fs::path(env.report.file).filename().string()}};
        writeLdChain(c, env.cube, calibration, "local-probe-ld", c.outputDirectory / "ld.ktx2");
    });
}

} // namespace

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

void runStage(const StageContext& c) {
    const std::string& kind = c.stage.kind;
    if (kind == "dfg-lut") return runDfg(c);
    if (kind == "environment") return runEnvironment(c);
    if (kind == "sun-extract") return runSun(c);
    if (kind == "specular-ld") return runSpecular(c);
    if (kind == "diffuse-sh") return runDiffuse(c);
    if (kind == "probe-ld") return runProbe(c);
    if (kind == "irradiance-cube") return runIrradiance(c);
    throw Error("scene: unknown stage kind '" + kind + "'");
}

} // namespace ibl
