// The stages of a scene's engine outputs (scene_stages.h): the glTF export and the material preview, by
// the library flows of `iblbake gltf` and `iblbake preview --reference`.
#include "iblbake/baker/gltf_export.h"
#include "iblbake/baker/material_preview.h"
#include "scene_stages.h"

namespace ibl {

using nlohmann::json;

void runGltfStage(const StageContext& c) {
    const json& s = c.stage.settings;
    GltfExportSource source{c.dependencies.at("specular") / "specular.ktx2",
                            c.dependencies.at("diffuse") / "diffuse.json", std::nullopt};
    if (c.dependencies.count("sun")) source.sun = c.dependencies.at("sun") / "sun.json";
    GltfExportSettings settings;
    settings.minFaceSize = s.value("minFaceSize", settings.minFaceSize);
    settings.quality = s.value("quality", settings.quality);
    GltfExport gltf;
    try {
        gltf = exportGltf(source, settings, c.outputDirectory / s.at("file").get<std::string>(),
                          [&]() -> const Executor& { return *c.executor; })
                   .gltf;
    } catch (const SettingError& e) {
        throw Error(c.name + ": outputs.gltf.minFaceSize: " + e.what());
    }
    writeJsonFile(c.outputDirectory / kEntryFiles.gltfFacts,
                  {{"levels", gltf.scene.specular.levels.size()},
                   {"faceSize", gltf.scene.specular.levels.front().faceSize},
                   {"intensity", gltfIblIntensity(gltf.scene)},
                   {"sun", gltf.scene.sun.has_value()}});
}

namespace {

RuntimeOptions previewOptions(const json& s) {
    RuntimeOptions options;
    options.energyCompensation = s.at("energyCompensation").get<bool>();
    options.diffuseModel = s.at("diffuseModel") == "disney" ? DiffuseModel::Disney : DiffuseModel::Lambert;
    options.specularTaps = s.at("specularLookup") == "taps";
    return options;
}

} // namespace

void runPreviewReferenceStage(const StageContext& c) {
    const json& s = c.stage.settings;
    // The full calibrated environment (before any sun extraction), at the bake's face size.
    const CubeMap environment = readCubeFile(c.dependencies.at("environment") / kEntryFiles.cube);
    MaterialPreviewSettings settings;
    settings.sphereSize = s.at("sphereSize").get<int>();
    settings.referenceTargetError = s.at("targetError").get<double>();
    if (c.waiting)
        c.waiting("reference", "first round of " + std::to_string(kPreviewColumns) + " roughness columns",
                  -1.0);
    const PreviewReference reference = renderPreviewReference(
        environment, previewOptions(s), settings, [&](int done, int columns, double secondsLeft) {
            if (c.waiting && done < columns)
                c.waiting("reference",
                          std::to_string(done) + " of " + std::to_string(columns) + " columns converged",
                          secondsLeft);
        });
    writePreviewReference(c.outputDirectory / kEntryFiles.previewReference,
                          c.outputDirectory / kEntryFiles.previewReferenceFacts, reference);
}

void runPreviewStage(const StageContext& c) {
    const json& s = c.stage.settings;
    const auto entry = [&](const char* id) { return c.dependencies.at(id); };
    PreviewBakeFiles files{entry("specular") / "specular.ktx2",
                           entry("dfg") / "dfg_lut.ktx2",
                           entry("diffuse") / "diffuse.json",
                           std::nullopt,
                           std::nullopt,
                           std::nullopt};
    if (c.dependencies.count("sun")) files.sun = entry("sun") / "sun.json";
    if (c.dependencies.count("irradiance")) files.irradiance = entry("irradiance") / "irradiance.ktx2";
    if (std::filesystem::exists(entry("specular") / kRoughLayersFile))
        files.roughLayers = entry("specular") / kRoughLayersFile;
    const ProbeSet set = loadPreviewProbeSet(files);
    MaterialPreviewSettings settings;
    settings.sphereSize = s.at("sphereSize").get<int>();
    settings.exposureEV = s.at("exposure").get<float>();
    const PreviewReference reference = readPreviewReference(
        entry("preview-reference") / kEntryFiles.previewReference,
        entry("preview-reference") / kEntryFiles.previewReferenceFacts, settings.sphereSize);
    const MaterialPreview preview = renderMaterialPreview(
        set, previewOptions(s), &reference, *c.executor, settings, c.outputDirectory / c.stage.products.at(0),
        c.outputDirectory / c.stage.products.at(1));
    writeJsonFile(
        c.outputDirectory / kEntryFiles.previewFacts,
        {{"width", preview.width},
         {"height", preview.height},
         {"roughness", preview.roughness},
         {"error",
          {{"dielectric", preview.dielectricError}, {"metal", preview.metalError}, {"both", preview.error}}},
         {"referenceErrorEstimate",
          {{"dielectric", preview.dielectricReferenceError},
           {"metal", preview.metalReferenceError},
           {"both", preview.referenceError}}}});
}

} // namespace ibl
