// One writer per product (docs/architecture.md "Where things live"): each builds its product's document (KTX2
// key/values, JSON, OpenEXR attributes) from typed values and writes it into an OutputSet, so that the
// single-product commands (`iblbake specular`, `diffuse`, `dfg`, `calibrate`) and the scene stages write
// the same bytes. They know nothing of the command line: paths and settings come in, what was stored comes
// out (for the caller's report and manifest).
#pragma once

#include "iblbake/baker/dfg_lut.h"
#include "iblbake/baker/environment.h"
#include "iblbake/baker/products.h"
#include "iblbake/baker/specular.h"
#include "iblbake/ktx2/output_set.h"

#include <nlohmann/json.hpp>

#include <filesystem>
#include <optional>
#include <string>

namespace ibl {

// How a KTX2 product cube was stored.
struct StoredCube {
    ProductStorage storage;
    Ktx2WriteStats stats;
};

// ---------------------------------------------------------------------------------------------------
// The LD chain ("specular-ld" or "local-probe-ld") and the distant chain's rough layers.

struct LdChainWriteSettings {
    LdChainProduct product; // its metadata; sunInLevel0 is decided here (withSun)
    Ktx2Format format = Ktx2Format::RGBA16F;
    bool clampToFormat = false;       // else stored with a storage scale
    std::string profile = "standard"; // ktx2/cube_profile.h kCubeProfileKey
    bool visibility = false;          // premultiplied alpha: a local probe's visibility (kVisibilityKey)
    const CubeMap* withSun = nullptr; // the cube before sun extraction: level 0 may keep the sun's pixels
};

struct LdChainWritten {
    bool sunInLevel0 = false;
    StoredCube chain;
    std::optional<StoredCube> roughLayers; // when baked.roughLayers is not empty
};

// Keeps the sun in level 0 where the format holds it (specular.h keepSunInLevel0), chooses the storage
// (chooseProductStorage), builds the key/values (ldChainKeyValues, roughLayerKeyValues, the cube profile)
// and writes `chainFile`, and with rough layers in `baked` `roughLayersFile`, each with a storage of its own.
LdChainWritten writeLdChainProduct(OutputSet& outputs, SpecularWithRoughLayers& baked,
                                   const LdChainWriteSettings& settings, const CalibrationRecord& record,
                                   const std::optional<DiskLight>& sun,
                                   const std::filesystem::path& chainFile,
                                   const std::filesystem::path& roughLayersFile = {});

// ---------------------------------------------------------------------------------------------------
// The irradiance cube (stores E / pi; docs/formats.md "Irradiance cube").

struct IrradianceCubeWriteSettings {
    std::string methodText; // products.h irradianceMethodText
    std::string colorSpace;
    std::optional<std::string> source; // the input's file name
    std::optional<LatLongPixels> latLongPixels;
    Ktx2Format format = Ktx2Format::RGBA16F;
    bool clampToFormat = false;
    std::string profile = "standard";
};

StoredCube writeIrradianceCubeProduct(OutputSet& outputs, CubeMap cube,
                                      const IrradianceCubeWriteSettings& settings,
                                      const CalibrationRecord& record, const std::optional<DiskLight>& sun,
                                      const std::filesystem::path& file);

// ---------------------------------------------------------------------------------------------------
// The DFG LUT: RGBA32F KTX2 (scene bakes), or a 3-channel OpenEXR in float or half (`iblbake dfg`).

enum class DfgLutFile { Ktx2, ExrFloat, ExrHalf };

void writeDfgLutProduct(OutputSet& outputs, const ImageRGBA& lut, std::uint32_t samples, DfgLutFile kind,
                        const std::filesystem::path& file);

// ---------------------------------------------------------------------------------------------------
// JSON documents.

// The iblbake.diffuse document (products.h diffuseDocument).
void writeDiffuseProduct(OutputSet& outputs, const DiffuseSH& sh, const std::string& requestedWindow,
                         const std::string& colorSpace, const DiffuseSource& source,
                         const CalibrationRecord& record, const std::optional<DiskLight>& sun,
                         const std::filesystem::path& file);

// The extracted sun's disk light (products.h sunJson): in lux when the map is calibrated; returns the text.
std::string writeSunProduct(OutputSet& outputs, const DiskLight& light, bool absolute,
                            const std::filesystem::path& file);

// ---------------------------------------------------------------------------------------------------
// Images for people and for other tools.

// The calibrated environment in its input's layout (environment.h calibrateInInputLayout) as float
// OpenEXR: a lat-long keeps the input's pixel grid (and OpenEXR's envmap attribute when its placement is
// OpenEXR's), a cube input is a vertical strip; the record and the sun as "iblbake:" attributes.
void writeCalibratedEnvironment(OutputSet& outputs, const CalibratedImage& calibrated,
                                const std::filesystem::path& file);

// One OpenEXR per level into `directory`: the six faces side by side in +X, -X, +Y, -Y, +Z, -Z order
// (OpenGL orientation), named level_<m>.exr, with the chain's roughness mapping (ldChainKeyValues': the
// product's mapping, or filament-lod and the level's r when its levels follow an engine profile's rule).
void writeLdChainExrLevels(OutputSet& outputs, const CubeMapChain& chain, const LdChainProduct& product,
                           const std::filesystem::path& directory);

} // namespace ibl
