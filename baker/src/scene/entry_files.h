// The names of the files a stage writes into its cache entry, one table for the stages that write them and
// the manifest, summaries and commands that read them (scene_stages.cpp, product_plans.cpp).
#pragma once

namespace ibl {

struct EntryFileNames {
    // Every environment-like entry ("environment", "sun"): the working-space cube and its calibration
    // (JSON: factor, absolute, units, colorSpace, record (products.h calibrationRecordToJson), source,
    // sunLight?).
    const char* cube = "cube.ktx2";
    const char* calibration = "calibration.json";
    // Beside the environment stage's cube: the input file as given ("file") and its report as the commands
    // print it (inspect.h ingestReportText, "text").
    const char* ingestReport = "ingest_report.json";
    // Beside the specular stage's chain: its manifest facts (products.h ldManifestFactsToJson, with
    // sunInLevel0), so that the manifest needs nothing else from the entry; for printing, per level its face
    // size and bake time ("levels") and what the writer repaired or clamped (ktx2.h Ktx2WriteStats:
    // "clampedTexels", "repairedNonFinite").
    const char* ldManifestFacts = "manifest_facts.json";
    const char* chainReport = "chain_report.json";
    // A command's views of the specular chain (`iblbake specular --exr, --preview`): every level as OpenEXR
    // in a directory, a tone-mapped PNG of every level.
    const char* ldExrDirectory = "levels";
    const char* ldPreview = "preview.png";
    // Beside a local probe's chain: whether it carries a visibility and the alpha values its ingest repaired
    // (products.h probeVisibilityFactsToJson).
    const char* probeVisibilityFacts = "visibility_facts.json";
    // Beside every KTX2 product of a stage (specular, irradiance, local probe): how it was stored
    // (products.h productStorageToJson), for the manifest and the bake summary.
    const char* storage = "storage.json";
    // Beside the diffuse stage's document: the SH window's report as the commands print it (sh.h
    // shWindowText, "text"). Beside an irradiance cube: its texels clamped to the format and, evaluated from
    // the SH, those clamped at 0 ("clampedTexels", "shNegativeTexels").
    const char* shReport = "sh_report.json";
    const char* irradianceReport = "irradiance_report.json";
    // Beside the engine outputs: what the manifest and the bake's report say about them
    // (engine_output_stages.cpp). gltf-export: {levels, faceSize, intensity, sun}; material-preview: {width,
    // height, roughness, error: {dielectric, metal, both}}.
    const char* gltfFacts = "gltf_facts.json";
    const char* previewFacts = "preview_facts.json";
    // The preview-reference stage's entry: the balls' reference (material_preview.h writePreviewReference).
    const char* previewReference = "reference.bin";
    const char* previewReferenceFacts = "reference_facts.json";
    // Beside the sun-in-probe check: {detected, and with a sun: warning, roughness, keptError,
    // extractedError} (sun_in_probe.h), which the manifest's warnings read.
    const char* sunInProbeFacts = "sun_in_probe.json";
};

inline constexpr EntryFileNames kEntryFiles{};

} // namespace ibl
