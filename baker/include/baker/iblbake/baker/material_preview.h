// The material preview (`iblbake preview` and a scene's outputs.preview): balls of perceptual roughness
// 0, 0.1, ..., 1 (columns), dielectric and metal, lit by a bake through the runtime module; with a
// reference environment, the brute-force render of the same balls against it and the relative error.
// Written as a labelled PNG grid (rows named, columns labelled with their roughness, the error colour
// scale with its values) and the linear panels as OpenEXR.
#pragma once

#include "iblbake/baker/latlong_pixels.h"
#include "iblbake/core/cubemap.h"
#include "iblbake/opencl/executor.h"
#include "iblbake/runtime/runtime.h"
#include "iblbake/runtime/runtime_reference.h"
#include "iblbake/scene/scene.h"

#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace ibl {

inline constexpr int kPreviewColumns = 11; // perceptual roughness c / 10

// ---------------------------------------------------------------------------------------------------
// Loading what the preview renders.

struct PreviewBake {
    ProbeSet set;
    RuntimeOptions options;
    double calibrationFactor = 1.0; // what the bake multiplied its input by (the reference gets the same)
};

// The distant lighting of a bake's files: the LD chain, the DFG LUT (.ktx2 as a scene bake writes it, or
// .exr as `iblbake dfg`), diffuse.json's SH, and the sun and irradiance cube when given.
struct PreviewBakeFiles {
    std::filesystem::path specular, dfg, diffuse;
    std::optional<std::filesystem::path> sun, irradiance, roughLayers;
};
ProbeSet loadPreviewProbeSet(const PreviewBakeFiles& files);

// A scene bake directory through its manifest.json, else the loose files of `iblbake dfg/specular/diffuse`
// (specular.ktx2, dfg_lut.exr, diffuse.json [, sun.json] [, irradiance.ktx2] [, specular_rough.ktx2: the
// chain's rough layers, `iblbake specular --rough-layers`]), whose calibration factor
// is recorded in specular.ktx2. Throws ibl::Error naming the file.
PreviewBake loadPreviewBake(const std::filesystem::path& directory);

// The reference environment: `file` ingested at the bake's mirror resolution (at least 128, so that a
// coarser reference does not blur what the runtime's level 0 shows sharply and count it as the runtime's
// error) with the lat-long pixel placement the bake used, and calibrated by `calibrationFactor`, the sun
// included.
CubeMap previewReferenceCube(const std::filesystem::path& file, double calibrationFactor, int baseFaceSize,
                             LatLongPixels latLongPixels);

// ---------------------------------------------------------------------------------------------------
// Rendering and writing.

struct MaterialPreviewSettings {
    int sphereSize = 96;     // pixels per ball
    float exposureEV = 0.0f; // exposure compensation in stops
    // The converged reference (runtime_reference.h renderAdaptiveReference): each roughness column at the
    // least effort whose own estimated error (relative, luminance, both rows) is at most this.
    double referenceTargetError = kPreviewReferenceTargetError;
};

// The converged reference of the preview's balls (renderAdaptiveReference, one group per roughness column:
// both balls of a column, as the preview reports its error), per point of materialPreviewPoints' order: its
// value and estimated error. It depends on the environment, the options and the ball size only, so a scene
// caches it apart from the bake it judges (issue 46).
struct PreviewReference {
    std::vector<glm::vec3> value, errorEstimate;
    std::size_t brightTexels = 0;
    std::vector<std::uint32_t> columnSamples; // per column: samples per strategy it stopped at
    std::vector<double> columnErrorEstimate;  // per column: its estimate, relative
};
// The balls' shading points (dielectric row 0, metal row 1, perceptual roughness c / 10 in column c) and
// each one's ball (row x kPreviewColumns + column).
std::vector<ShadingPoint> materialPreviewPoints(int sphereSize, std::vector<int>& ballOfPoint);
PreviewReference renderPreviewReference(const CubeMap& environment, const RuntimeOptions& options,
                                        const MaterialPreviewSettings& settings,
                                        const ReferenceProgress& progress = {});
// As a binary file of little-endian floats (a point count, then value and estimate per point) beside a
// JSON document of the rest; read back checked against the ball size's point count. Throw ibl::Error
// naming the file.
void writePreviewReference(const std::filesystem::path& binary, const std::filesystem::path& facts,
                           const PreviewReference& reference);
PreviewReference readPreviewReference(const std::filesystem::path& binary, const std::filesystem::path& facts,
                                      int sphereSize);

struct MaterialPreview {
    std::vector<float> roughness; // per column
    // Relative mean luminance error per column, sum |runtime - reference| / sum reference over the balls'
    // pixels: each row's and both rows'. Empty without a reference.
    std::vector<double> dielectricError, metalError, error;
    // The reference's own estimated error per column (sum of the points' ConvergedReference::errorEstimate
    // luminance / sum reference): how far the error above may be off. Each row's and both rows'; empty
    // without a reference.
    std::vector<double> dielectricReferenceError, metalReferenceError, referenceError;
    std::size_t referenceBrightTexels = 0; // integrated deterministically by the reference
    int width = 0, height = 0;             // of the PNG grid
};

// The grid's geometry (all in pixels), from the ball size, whether reference and error rows are shown, and
// the groups of rows (dielectric and metal; the light preview's lights) and roughness columns.
struct PreviewLayout {
    int sphereSize = 0, fontSize = 0, margin = 0;
    int columnCount = kPreviewColumns;
    int groupCount = 2;
    int columnWidth = 0;  // the ball, or wider for small balls: room for a column's labels
    int labelWidth = 0;   // the row names' column at the left
    int headerHeight = 0; // the caption and the roughness labels above the balls
    int rowCount = 0;     // groupCount (runtime) or 3 x groupCount (runtime, reference, error of each group)
    int groupGap = 0;     // between groups of rows
    int legendHeight = 0; // the error colour scale below (0 without a reference)
    int width = 0, height = 0;
    int cellX(int column) const; // left edge of a column's balls (centred in the column)
    int cellY(int row) const;    // top edge of a row's balls
};
PreviewLayout previewLayout(int sphereSize, bool withReference, int groupCount = 2,
                            int columnCount = kPreviewColumns);
// The row names, top to bottom: "runtime G" [, "reference G", "error G"] for each group G.
std::vector<std::string> previewRowNames(bool withReference,
                                         const std::vector<std::string>& groups = {"dielectric", "metal"});

// 0 black, 5% blue, 10% yellow, 20% and more red (display-referred).
glm::vec3 previewErrorColor(float relativeError);

// Renders and writes `png` (the labelled grid, 8-bit sRGB) and `exr` (runtime | reference | error panels
// side by side, linear). `reference`: the full calibrated environment, or nullptr for the runtime alone.
// Throws ibl::Error naming the file; the labels need DejaVu Sans (Debian fonts-dejavu-core).
MaterialPreview renderMaterialPreview(const ProbeSet& set, const RuntimeOptions& options,
                                      const CubeMap* reference, const Executor& executor,
                                      const MaterialPreviewSettings& settings,
                                      const std::filesystem::path& png, const std::filesystem::path& exr);

// `iblbake preview`'s error lines (none without a reference): the runtime's relative mean error per roughness
// column, and the reference's own estimate.
std::string materialPreviewErrorText(const MaterialPreview& preview);
// The same with the reference already rendered (renderPreviewReference of the same settings), or nullptr.
MaterialPreview renderMaterialPreview(const ProbeSet& set, const RuntimeOptions& options,
                                      const PreviewReference* reference, const Executor& executor,
                                      const MaterialPreviewSettings& settings,
                                      const std::filesystem::path& png, const std::filesystem::path& exr);

// The flow of `iblbake preview BAKE_DIR [--reference HDRI]`: the bake's balls (loadPreviewBake), beside the
// reference of `referenceHdri` (previewReferenceCube at the placement `latLongPixels`) unless it is empty,
// written to `png` and `exr`; `executor` is asked for once the files have been read. `text`: the report's
// lines after the files' (the probe, materialPreviewErrorText).
struct BakeDirectoryPreview {
    MaterialPreview preview;
    std::string text;
};
BakeDirectoryPreview previewBakeDirectory(const std::filesystem::path& bakeDirectory,
                                          const std::filesystem::path& referenceHdri,
                                          LatLongPixels latLongPixels,
                                          const std::function<const Executor&()>& executor,
                                          const MaterialPreviewSettings& settings,
                                          const std::filesystem::path& png, const std::filesystem::path& exr);

} // namespace ibl
