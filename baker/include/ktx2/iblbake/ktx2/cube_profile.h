// Target profiles of the cube KTX2 products (`--profile` of `iblbake specular` / `diffuse`, the scene's
// outputs.profile), recorded in every cube as the key iblbake.profile and in the scene manifest.
// - standard: docs/conventions.md's cube (OpenGL faces and face orientation in a right-handed, +Y-up frame).
// - three: what three.js r187's cube-texture path shows right. three samples a CubeTexture that is not
//   a render target at (-x, y, z) of the world direction (flipEnvMap = -1 in scene.background's box,
//   PMREMGenerator.fromCubemap and MeshStandardMaterial.envMap), so the stored cube is ours mirrored in
//   x: +X and -X faces swapped, the columns of every face reversed. `iblbake specular`'s chain also holds
//   at each level the roughness three reads there (kEngineProfiles' row, LevelRule::FilamentLod), so three
//   samples it as its own PMREM (baker/runtime/js/iblbakeCubeLoader.js marks it isPMREMTexture).
// writeKtx2Cube stores the layout its iblbake.profile key declares; readKtx2 returns every cube in the
// standard layout, so iblbake's own readers (runtime, `iblbake gltf`) never see the difference.
#pragma once

#include "iblbake/core/image.h"

#include <mip_mapping.h>

#include <span>
#include <string>
#include <vector>

namespace ibl {

enum class CubeProfile { Standard, Three };
inline const std::vector<std::string> kCubeProfileNames = {"standard", "three"};
inline constexpr const char* kCubeProfileKey = "iblbake.profile";

// Engine profiles, one row per consumer (docs/engines.md "Engine profiles"): what each engine's own lookup
// reads, derived from its shader source, so that a bake for it holds at each level exactly the roughness the
// engine reads there, in the encoding it decodes and with the SH as it applies them.
// - levelRule: which perceptual roughness level m of N holds. Baked: as the bake's --mip-mapping says (the
//   runtime and probe.glsl read the mapping from the file). FilamentLod: lod = maxLod r (2 - r), so level m
//   holds r = 1 - sqrt(1 - m / (N - 1)): three.js r187's roughnessToMip (envmap_common_pars_fragment,
//   "Matches Filament's perceptualRoughnessToLod()"; PMREMGenerator.lodToRoughness is its inverse), with
//   ENVMAP_MAX_LOD = the texture's mip count - 1 (WebGLPrograms), and Filament 1.53's lookup
//   (surface_light_indirect.fs perceptualRoughnessToLod, iblRoughnessOneLevel = the reflections' level count
//   - 1, set per view from the IndirectLight). BabylonLodFromAlphaG:
//   Babylon.js 9.28's PBR shader reads lod = log2(S alphaG) x lodGenerationScale + lodGenerationOffset
//   (pbrBlockReflection sampleReflectionTexture, getLodFromAlphaG) with alphaG = r^2 + MINIMUMVARIANCE
//   (convertRoughnessToAverageSlope) and S the level-0 face size; its glTF loader's EXT_lights_image_based
//   sets lodGenerationScale = (N - 1) / log2(S) and offset 0 (RawCubeTexture.updateRGBDAsync), and leaves
//   linearSpecularLOD false. So level m (m >= 1) holds alphaG = S^(m / (N - 1) - 1), r = sqrt(alphaG -
//   MINIMUMVARIANCE); level 0 is the unconvolved source, which Babylon reads for every r up to level 0's.
// - smallestFace: the default face size of the chain's last level (the extension suggests 16; three's
//   PMREMGenerator stops at 8-px faces, LOD_MIN = 3, and its shader reads the last level as irradiance / pi,
//   getIBLIrradiance; Filament's cmgen stops at 16).
// - mirrorX: the stored cube is ours mirrored in x (three.js samples a cube texture at (-x, y, z)).
// - decodeGamma: the engine raises decoded texels to this power before use. Babylon's glTF loader leaves
//   its RawCubeTexture's gammaSpace true, so its shaders run toLinearSpace (pow 2.2, GAMMAREFLECTION)
//   after the RGBD decode: the file stores value^(1 / 2.2).
// - shIntensityPower: how many times the engine multiplies the SH by the light's intensity. Babylon's loader
//   scales the harmonics by `intensity` and its PBR shader multiplies the irradiance by the texture's level
//   (= intensity) again (computeEnvironmentIrradiance): the file divides the coefficients by intensity^2.
enum class LevelRule { Baked, FilamentLod, BabylonLodFromAlphaG };
inline constexpr const char* kFilamentLodRuleName = kFilamentLodMappingName; // mip_mapping.h FilamentLod
inline constexpr const char* kFilamentLodRuleMeaning =
    "level m of L holds r = 1 - sqrt(1 - m/(L-1)) (lod = (L-1) r (2 - r): three.js r187 roughnessToMip, "
    "Filament perceptualRoughnessToLod)";
struct EngineProfile {
    const char* name;
    const char* consumer;
    LevelRule levelRule;
    double minimumVariance; // BabylonLodFromAlphaG: alphaG = r^2 + this (Babylon's MINIMUMVARIANCE)
    int smallestFace;
    bool mirrorX;
    double decodeGamma;
    int shIntensityPower;
    const char* storage; // texel encoding and storage
    const char* sh;      // the SH convention (docs/engines.md has the derivations)
    // The fewest levels of the profile's chain, going below smallestFace for a small base: three's
    // PMREMGenerator upsamples inputs below 256 px (MIN_SIZE) so that every PMREM has 6 levels, and its
    // lookup's roughness steps follow the count (a 128-px chain down to 8 px has 5: measured 2.5% against
    // 1.9% at r = 0.2 with 6, docs/engines.md "Render fidelity in three.js").
    int minLevels = 1;
};
inline constexpr EngineProfile kEngineProfiles[] = {
    {"standard", "iblbake runtime, probe.glsl, KTX2 readers", LevelRule::Baked, 0.0, 1, false, 1.0, 1,
     "RGBA16F/RGBA32F cube KTX2, linear, x storageScale", "diffuse.json: A_l k_i L_i, our basis"},
    {"three", "three.js r187 (iblbakeCubeLoader.js: a PMREM texture, used as is)", LevelRule::FilamentLod,
     0.0, 8, true, 1.0, 1, "RGBA16F/RGBA32F cube KTX2 mirrored in x, linear, x storageScale",
     "diffuse.json: A_l k_i L_i, our basis; three's shader reads the last level as irradiance / pi", 6},
    {"babylon", "Babylon.js 9.28 glTF loader (EXT_lights_image_based)", LevelRule::BabylonLodFromAlphaG,
     0.0005, 16, false, 2.2, 2, "RGBD PNG of value^(1/2.2) / intensity",
     "irradianceCoefficients: Babylon's basis and frame, E_i / intensity^2"},
    {"filament", "Filament 1.53 (Ktx1Reader, IndirectLight; cmgen --deploy's files)", LevelRule::FilamentLod,
     0.0, 16, false, 1.0, 1, "R11G11B10F cube KTX1, linear radiance (0..65,024 R, G; 0..64,512 B)",
     "KTX1 key sh and sh.txt: A_l k_i L_i / pi, Filament's polynomial basis"},
};

// The row named `name`; throws ibl::Error "'<name>' is not one of standard, three, babylon, filament".
const EngineProfile& engineProfile(const std::string& name);
// The perceptual roughness level m of a chain of levelCount levels on level-0 faces of baseFaceSize texels
// must hold for the profile's engine (FilamentLod, BabylonLodFromAlphaG; 0 for level 0 and for Baked).
float engineLevelRoughness(const EngineProfile& profile, int level, int levelCount, int baseFaceSize);
// The same for every level of the chain (SpecularSettings::levelRoughness of a chain baked for the engine).
std::vector<float> engineChainRoughness(const EngineProfile& profile, int levelCount, int baseFaceSize);
// The levels of the profile's chain on level-0 faces of baseFaceSize texels: down to its smallestFace, at
// least its minLevels, at most the full chain down to 1 x 1.
int engineLevelCount(const EngineProfile& profile, int baseFaceSize);

// Throws ibl::Error "'<name>' is not one of standard, three" for any other name.
CubeProfile parseCubeProfile(const std::string& name);
const char* cubeProfileName(CubeProfile profile);

// Mirrors six faces (+X, -X, +Y, -Y, +Z, -Z) in x, in place: the three profile's layout from the
// standard one and back (the mirror is its own inverse).
void mirrorCubeFacesX(std::span<ImageRGBA> faces);

} // namespace ibl
