// The products' documents, built in one place from typed values (a CalibrationRecord, the extracted sun,
// the settings): the KTX2 key/values of the specular chain, the irradiance cube, the DFG LUT and the local
// probes; the `iblbake.diffuse` JSON document; the manifest entries; the calibration and sun metadata they
// all carry. `iblbake specular/diffuse/dfg`, the scene stages and the exporters call these, so that a
// product says the same thing whichever command wrote it.
#pragma once

#include "iblbake/baker/calibration.h"
#include "iblbake/baker/irradiance.h"
#include "iblbake/baker/latlong_pixels.h"
#include "iblbake/baker/sh.h"
#include "iblbake/baker/sun.h"
#include "iblbake/ktx2/ktx2.h"

#include <mip_mapping.h>

#include <nlohmann/json.hpp>

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace ibl {

// The whole file; throws ibl::Error "<file>: cannot read".
std::string readText(const std::filesystem::path& path);

// ---------------------------------------------------------------------------------------------------
// Calibration and sun

// calibrationMetadata(record, prefix) plus prefix + "sun" ("extracted as a disk light ..." or "kept in the
// environment") and, when extracted, prefix + "sunLight" = the light's one-line sunJson. Prefix "iblbake."
// for KTX2 key/values, "iblbake:" for OpenEXR attributes.
Ktx2KeyValues calibrationKeyValues(const CalibrationRecord& record, const std::optional<DiskLight>& sun,
                                   const std::string& prefix = "iblbake.");

// The light's JSON document (sun.h diskLightToJson), in lux when the record calibrated the map and in
// relative units otherwise; indent < 0: one line.
std::string sunJson(const DiskLight& light, const CalibrationRecord& record, int indent = 2);

// The record with typed values, for files the bake reads back (a scene stage's cache entry), and its
// reader (throws ibl::Error naming the first missing or malformed key).
nlohmann::json calibrationRecordToJson(const CalibrationRecord& record);
CalibrationRecord calibrationRecordFromJson(const nlohmann::json& json);

// ---------------------------------------------------------------------------------------------------
// The source's lat-long pixel placement (latlong_pixels.h), recorded by every product of a lat-long source:
// KTX2 key "iblbake.latlongPixels", OpenEXR attribute "iblbake:latlongPixels", glTF extras
// "iblbake.latlongPixels", and "latlongPixels" in the diffuse document's and calibration.json's "source"
// and at the top of the manifest; the value is "centre" or "openexr". Products of cube inputs carry none
// (the key is absent: their source has no lat-long pixels), as do files written before it was recorded.

extern const char* const kLatLongPixelsKey; // "latlongPixels", without prefix
Ktx2KeyValues latLongPixelsKeyValues(const std::optional<LatLongPixels>& placement,
                                     const std::string& prefix = "iblbake.");
// Sets object["latlongPixels"] when there is a placement; latLongPixelsFromJson reads it back (nothing when
// absent; throws ibl::Error for a value that is not centre or openexr).
void addLatLongPixels(nlohmann::json& object, const std::optional<LatLongPixels>& placement);
std::optional<LatLongPixels> latLongPixelsFromJson(const nlohmann::json& object);

// ---------------------------------------------------------------------------------------------------
// KTX2 products

// The DFG LUT's metadata (KTX2 key/values, or with prefix "iblbake:" OpenEXR attributes): product, layout,
// samples. `rowWord` names a row of the image in the layout text ("row" in KTX2, "scanline" in OpenEXR).
Ktx2KeyValues dfgLutMetadata(const std::string& prefix, const std::string& rowWord, std::uint32_t samples);

// An LD chain: the distant specular ("specular-ld") or a local probe's ("local-probe-ld").
struct LdChainProduct {
    std::string product = "specular-ld";
    MipMapping mapping = MipMapping::Frostbite;
    int levelCount = 0;
    std::optional<int> integratedLevels; // recorded when the bake stopped integrating early (scene bakes)
    std::string colorSpace;
    std::optional<std::string> source;          // the input's file name
    std::optional<LatLongPixels> latLongPixels; // the input's, when a lat-long (IngestReport)
    std::string settings;                       // "quality=... samples=..." as the writer ran it
    bool sunInLevel0 = false;                   // specular.h keepSunInLevel0
    // With sunInLevel0: the detection limit the sun was extracted with (`iblbake gltf` finds it again).
    std::optional<double> sunMaxSolidAngle;
    // An engine profile's own level rule (cube_profile.h FilamentLod), when the levels follow it instead of
    // `mapping`: the perceptual roughness of every level (level 0: 0).
    std::vector<float> levelRoughness;
};
// "iblbake.product", "iblbake.roughnessMapping" (mipMappingName: frostbite | linear; with levelRoughness
// the rule's name, filament-lod, and "iblbake.levelRoughness" the levels' roughness, comma-separated),
// "iblbake.roughnessMappingMeaning" (mipMappingMeaning), "iblbake.levelCount", "iblbake.integratedLevels",
// "iblbake.colorSpace", "iblbake.source", "iblbake.latlongPixels", "iblbake.settings", calibrationKeyValues,
// "iblbake.sunInLevel0" = "true" and "iblbake.sunMaxSolidAngle" when level 0 kept the sun.
Ktx2KeyValues ldChainKeyValues(const LdChainProduct& chain, const CalibrationRecord& record,
                               const std::optional<DiskLight>& sun);

// The rough layers beside the distant chain ("specular-rough-layers", kernels/mip_mapping.h):
// "iblbake.product", "iblbake.roughLayerRoughness" (roughLayerRoughnessText), "iblbake.roughLayerMeaning",
// "iblbake.colorSpace", "iblbake.source", "iblbake.settings", calibrationKeyValues. The runtime's
// loadRoughLayersKtx2 checks the roughness key (kRoughLayerRoughnessKey, kernels/mip_mapping.h).
inline constexpr const char* kRoughLayerProduct = "specular-rough-layers";
Ktx2KeyValues roughLayerKeyValues(const LdChainProduct& chain, const CalibrationRecord& record,
                                  const std::optional<DiskLight>& sun);

// The irradiance cube's normalization (E / pi), as its KTX2 key and the diffuse document state it.
extern const char* const kIrradianceNormalization;
// "sampled: ..." with the sample count, or "sh: ..." (the windowed SH evaluated per texel).
std::string irradianceMethodText(IrradianceMethod method, std::uint32_t samples);
Ktx2KeyValues irradianceKeyValues(const std::string& methodText, const std::string& colorSpace,
                                  const std::optional<std::string>& source,
                                  const std::optional<LatLongPixels>& latLongPixels,
                                  const CalibrationRecord& record, const std::optional<DiskLight>& sun);

// ---------------------------------------------------------------------------------------------------
// Float storage (docs/conventions.md "Float storage and the storage scale"; the key and its readers:
// iblbake/ktx2/storage_scale.h)

// How a product cube goes into its format: times a storage scale so that nothing clamps (the default), or
// clamped to the format's range when the user asked for that, with the energy the clamp loses.
struct ProductStorage {
    double scale = 1.0;                    // stored RGB = radiance x scale (KTX2 "iblbake.storageScale")
    bool clamped = false;                  // clamped to the format's range on request (scale stays 1)
    std::vector<double> energyLostPercent; // with `clamped`, per level: 100 (1 - E_clamped / E)
};

// The energy of a level: sum over its texels of (R + G + B) x the texel's exact solid angle (finite
// values; fp64), what ProductStorage's energyLostPercent compares.
double levelEnergy(const CubeMap& level);

// Without clampToFormat: the largest power of two <= 1 such that every finite channel of every level times
// it fits `format` (ktx2LargestValues; RGBA32F: always 1). With clampToFormat: scale 1 and the energy lost
// per level when every channel is clamped to the format's range.
ProductStorage chooseProductStorage(const CubeMapChain& chain, Ktx2Format format, bool clampToFormat);

// "iblbake.storageScale" (decimal, exact: a power of two), "iblbake.storageScaleMeaning", and with
// `clamped` "iblbake.storageClamped" (the energy lost per level).
Ktx2KeyValues storageKeyValues(const ProductStorage& storage);

// writeKtx2Cube of the chain times storage.scale, with keyValues and storageKeyValues(storage).
Ktx2WriteStats writeProductCube(const std::filesystem::path& path, const CubeMapChain& chain,
                                Ktx2Format format, const Ktx2KeyValues& keyValues,
                                const ProductStorage& storage, Ktx2Alpha alpha = Ktx2Alpha::Straight);

// writeKtx2CubeArray of the layers times storage.scale (chosen by chooseProductStorage over the layers as
// levels), with keyValues and storageKeyValues(storage).
Ktx2WriteStats writeProductCubeArray(const std::filesystem::path& path, const std::vector<CubeMap>& layers,
                                     Ktx2Format format, const Ktx2KeyValues& keyValues,
                                     const ProductStorage& storage);

// The manifest entry's keys (docs/formats.md "Manifest"): "storageScale", and with `clamped` "storageClamp"
// {"energyLostPercent": [per level], "meaning"}; the same object is a stage's cache record. Its reader
// throws ibl::Error naming the key.
nlohmann::json productStorageToJson(const ProductStorage& storage);
// The commands' "storage" line of a product written to `file` in `format` (bake_state.h storageLine).
std::string storageText(const std::filesystem::path& file, const std::string& format,
                        const ProductStorage& storage);
ProductStorage productStorageFromJson(const nlohmann::json& json);

// ---------------------------------------------------------------------------------------------------
// The iblbake.diffuse document (schemaVersion 1; docs/formats.md "Diffuse probes")

struct DiffuseSource {
    std::string file; // as the writer names it (the command's argument, or the scene's file name)
    int width = 0, height = 0;
    std::string layout, inputColorSpace;
    int faceSize = 0; // of the cube the SH were projected from
    double rotateDegrees = 0.0;
    std::optional<LatLongPixels> latLongPixels; // a lat-long input's placement
};
// schema, schemaVersion, generator, source (with latlongPixels for a lat-long), colorSpace, units,
// calibration (the record's keys without prefix, "sun", and "sunLight" as a light object when extracted),
// directions, sh {order, coefficientCount, basis, basisOrder, clampedCosineFactors, window {..., requested},
// minIrradiance, radianceUnwindowed, radiance, irradiance, irradianceOverPi and their conventions}; the same
// from `iblbake diffuse` and a scene bake (one stage writes it).
nlohmann::json diffuseDocument(const DiffuseSH& sh, const std::string& requestedWindow,
                               const std::string& colorSpace, const DiffuseSource& source,
                               const CalibrationRecord& record, const std::optional<DiskLight>& sun);

// ---------------------------------------------------------------------------------------------------
// Manifest entries (docs/formats.md "Manifest"); contentHash is the product file's.

nlohmann::json dfgManifestEntry(std::uint32_t size, std::uint32_t samples, bool disneyChannelUsed,
                                const std::string& contentHash);

struct LdManifestFacts {
    std::string file, format;
    int faceSize = 0, levels = 0, integratedLevels = 0;
    MipMapping mapping = MipMapping::Frostbite;
    double validRoughnessMax = 1.0;
    std::string quality;
    std::optional<bool> sunInLevel0; // the distant chain's (absent for local probes)
    // The distant chain's rough layers (docs/formats.md "Rough layers"), when baked: the manifest's
    // "roughLayers"
    // {"file", "faceSize", "layerCount", "roughness", "meaning", "storageScale" ...}.
    struct RoughLayers {
        std::string file;
        int faceSize = 0;
        ProductStorage storage;
    };
    std::optional<RoughLayers> roughLayers;
};
nlohmann::json ldManifestEntry(const LdManifestFacts& facts, const std::string& contentHash);
// The stage-side form of ldManifestEntry (no contentHash): what the specular stage records in its cache
// entry so that the manifest needs nothing else from it; and its reader.
nlohmann::json ldManifestFactsToJson(const LdManifestFacts& facts);
LdManifestFacts ldManifestFactsFromJson(const nlohmann::json& json);

// A local probe's visibility (Frostbite 2014 4.9.1.2; ingest.h IngestSettings::readAlpha): whether its chain
// carries one, and the alpha values of its capture repaired on ingest (ingest.h IngestReport). The probe
// stage's cache record; its reader throws ibl::Error naming the entry.
struct ProbeVisibilityFacts {
    bool visibility = false;
    std::uint64_t alphaNanRepaired = 0, alphaNegativeRepaired = 0, alphaOverOneRepaired = 0;
};
nlohmann::json probeVisibilityFactsToJson(const ProbeVisibilityFacts& facts);
ProbeVisibilityFacts probeVisibilityFactsFromJson(const nlohmann::json& json);
// The manifest's keys of a local probe (docs/formats.md "Manifest"): with a visibility, "visibility"
// {"convention": "premultiplied-alpha", "channel": "A", "meaning"}; with repaired alpha values,
// "alphaRepaired" {"nan", "negative", "overOne"}; nothing for a capture without alpha (every manifest before
// visibility existed).
void addProbeVisibilityToManifest(nlohmann::json& probeEntry, const ProbeVisibilityFacts& facts);

// From the diffuse document: sh.irradiance, its convention, sh.window {name, parameter, searched,
// bandFactors}.
nlohmann::json diffuseManifestEntry(const nlohmann::json& diffuseDocument, const std::string& contentHash);
nlohmann::json irradianceManifestEntry(int faceSize, const std::string& format, std::uint32_t samples,
                                       const std::string& contentHash);
nlohmann::json sunManifestEntry(const DiskLight& light, const std::string& contentHash);
// The manifest's "units", "colorSpace" and "calibration" {factor, record} of a bake.
void addCalibrationToManifest(nlohmann::json& manifest, const CalibrationRecord& record,
                              const std::string& colorSpace);

} // namespace ibl
