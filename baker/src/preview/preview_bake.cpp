// What the material preview renders (iblbake/baker/material_preview.h): a bake's probe set and the
// reference environment.
#include "../ingest/ingest_internal.h"
#include "iblbake/baker/calibration.h"
#include "iblbake/baker/ingest.h"
#include "iblbake/baker/material_preview.h"
#include "iblbake/baker/products.h"
#include "iblbake/baker/sun.h"
#include "iblbake/core/error.h"
#include "iblbake/core/format_text.h"
#include "iblbake/ktx2/ktx2.h"
#include "iblbake/runtime/runtime_manifest.h"
#include "iblbake/scene/scene_plan.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <charconv>
#include <cmath>

namespace ibl {

namespace {

namespace fs = std::filesystem;

// The LUT's R, G, B as stored (ingest's reader: OpenEXR files need no OpenImageIO).
ImageRGBA readDfgExr(const fs::path& path) {
    return ingest::readImage(path).pixels;
}

// The "iblbake.calibration.factor" value of a bake's KTX2: a finite, positive number and nothing else.
double calibrationFactorFrom(const std::string& text, const fs::path& file) {
    double factor = 0.0;
    const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), factor);
    if (error != std::errc() || end != text.data() + text.size() || !std::isfinite(factor) || factor <= 0.0)
        throw Error(file.string() + ": iblbake.calibration.factor " + quotedForMessage(text) +
                    " is not a positive number");
    return factor;
}

} // namespace

ProbeSet loadPreviewProbeSet(const PreviewBakeFiles& files) {
    LdPyramid ld = loadLdKtx2(files.specular);
    DfgTable dfg =
        files.dfg.extension() == ".ktx2" ? loadDfgKtx2(files.dfg) : dfgTableFromImage(readDfgExr(files.dfg));
    nlohmann::json diffuse;
    try {
        diffuse = nlohmann::json::parse(readText(files.diffuse));
    } catch (const nlohmann::json::exception& e) {
        throw Error(files.diffuse.string() + ": " + e.what());
    }
    std::array<glm::vec3, 9> irradiance{};
    const auto& coefficients = diffuse.at("sh").at("irradiance");
    if (coefficients.size() != 9) throw Error(files.diffuse.string() + ": sh.irradiance needs 9 entries");
    for (int i = 0; i < 9; ++i)
        irradiance[i] = glm::vec3(coefficients[i][0].get<float>(), coefficients[i][1].get<float>(),
                                  coefficients[i][2].get<float>());
    ProbeSet set(std::move(ld), std::move(dfg), shCoefficientsFrom(irradiance, false));
    if (files.sun) set.setSun(sunDiskFrom(diskLightFromJson(readText(*files.sun))));
    if (files.irradiance) set.setIrradianceCube(loadIrradianceKtx2(*files.irradiance));
    if (files.roughLayers) set.setRoughLayers(loadRoughLayersKtx2(*files.roughLayers));
    return set;
}

PreviewBake loadPreviewBake(const fs::path& dir) {
    if (fs::exists(dir / "manifest.json")) {
        ManifestProbeSet m = loadProbeSetFromManifest(dir / "manifest.json");
        return {std::move(m.set), m.options, m.calibrationFactor};
    }
    PreviewBakeFiles files{dir / "specular.ktx2", dir / "dfg_lut.exr", dir / "diffuse.json", {}, {}, {}};
    if (fs::exists(dir / "sun.json")) files.sun = dir / "sun.json";
    if (fs::exists(dir / "irradiance.ktx2")) files.irradiance = dir / "irradiance.ktx2";
    if (fs::exists(dir / kRoughLayersFile)) files.roughLayers = dir / kRoughLayersFile;
    PreviewBake bake{loadPreviewProbeSet(files), RuntimeOptions{}, 1.0};
    const Ktx2Image ktx = readKtx2(files.specular);
    if (auto it = ktx.keyValues.find("iblbake.calibration.factor"); it != ktx.keyValues.end())
        bake.calibrationFactor = calibrationFactorFrom(it->second, files.specular);
    return bake;
}

CubeMap previewReferenceCube(const fs::path& file, double calibrationFactor, int baseFaceSize,
                             LatLongPixels latLongPixels) {
    IngestSettings ingest;
    ingest.sourceFaceSize = std::max(128, baseFaceSize);
    ingest.latLongPixels = latLongPixels;
    SourceEnvironment env = ingestEnvironment({file}, ingest);
    applyCalibration(env.cube, calibrationFactor);
    return std::move(env.cube);
}

BakeDirectoryPreview
previewBakeDirectory(const std::filesystem::path& bakeDirectory, const std::filesystem::path& referenceHdri,
                     LatLongPixels latLongPixels, const std::function<const Executor&()>& executor,
                     const MaterialPreviewSettings& settings, const std::filesystem::path& png,
                     const std::filesystem::path& exr) {
    const PreviewBake bake = loadPreviewBake(bakeDirectory);
    std::optional<CubeMap> reference;
    if (!referenceHdri.empty())
        reference = previewReferenceCube(referenceHdri, bake.calibrationFactor,
                                         int(bake.set.distantLd().layout.baseFaceSize), latLongPixels);
    BakeDirectoryPreview out;
    out.preview = renderMaterialPreview(bake.set, bake.options, reference ? &*reference : nullptr, executor(),
                                        settings, png, exr);
    out.text = formatText("probe   LD chain of %u levels%s\n", bake.set.distantLd().layout.levelCount,
                          bake.set.roughLayers().layerCount != 0 ? " and its rough layers" : "") +
               materialPreviewErrorText(out.preview);
    return out;
}

} // namespace ibl
