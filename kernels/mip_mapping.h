// The roughness <-> mip-level mapping of an LD chain (docs/conventions.md "Roughness and the LD chain"), one
// source for the baker, the runtime and the kernels. Level 0 is the unconvolved source; level m of L holds
//   frostbite  r_m = (m / (L - 1))^2, so lod(r) = sqrt(r) (L - 1)   (Frostbite eq. 63, the default)
//   linear     r_m = m / (L - 1),     so lod(r) = r (L - 1)
//   filament-lod  r_m = 1 - sqrt(1 - m / (L - 1)), so lod(r) = r (2 - r) (L - 1)   (`--profile three`)
// with r the perceptual roughness. A chain has at most floor(log2(base face size)) + 1 levels (down to 1x1).
// Files store the mapping as its name (KTX2 key "iblbake.roughnessMapping", the manifest's
// "roughnessMapping"); files written before held prose after the name ("frostbite: level m of L holds ..."),
// which mipMappingFromStoredValue still reads.
#ifndef IBL_MIP_MAPPING_H
#define IBL_MIP_MAPPING_H

#include "portable.h"
#ifdef __cplusplus // the names of the mappings, below
#include <array>
#include <cctype>
#include <charconv>
#include <optional>
#include <string>
#include <string_view>
#include <vector>
#endif

IBL_BEGIN_NAMESPACE

#define IBL_MIP_FROSTBITE 0u
#define IBL_MIP_LINEAR 1u
// The engines' lookup lod = maxLevel r (2 - r) (three.js r187 roughnessToMip, Filament
// perceptualRoughnessToLod): what `--profile three` chains hold (cube_profile.h LevelRule::FilamentLod).
#define IBL_MIP_FILAMENT_LOD 2u

// Levels of a full chain whose level 0 has faces of faceSize texels (>= 1): floor(log2(faceSize)) + 1.
IBL_FN uint mipLevelCountForFaceSize(uint faceSize) {
    uint levels = 1u;
    while ((faceSize >> levels) != 0u)
        ++levels;
    return levels;
}

// The perceptual roughness level m of a chain of levelCount levels holds (0 for a one-level chain).
IBL_FN float mipLevelRoughness(uint mapping, uint level, uint levelCount) {
    if (levelCount <= 1u) return 0.0f;
    float t = IBL_FLOAT(level) / IBL_FLOAT(levelCount - 1u);
    if (mapping == IBL_MIP_FILAMENT_LOD) return 1.0f - sqrt(fmax(1.0f - t, 0.0f)); // r (2 - r) = t
    return mapping == IBL_MIP_LINEAR ? t : t * t;
}

// The fractional level (LOD) that holds perceptual roughness r, clamped to [0, 1] first.
IBL_FN float mipLevelForRoughness(uint mapping, float perceptualRoughness, uint levelCount) {
    float r = saturate(perceptualRoughness);
    float maxLevel = IBL_FLOAT(levelCount - 1u);
    if (mapping == IBL_MIP_FILAMENT_LOD) return r * (2.0f - r) * maxLevel;
    return (mapping == IBL_MIP_LINEAR ? r : sqrt(r)) * maxLevel;
}

// Rough layers: a chain's coarse levels cannot hold their lobes (a trilinear lookup of a 256-px chain is
// 3-40% off the exact LD at r >= 0.6 on the shared HDRIs, and 1-12% at r = 0.25-0.55: faces of 16 px and
// less, 0.06-0.2 apart in r), so a bake may add a cube array of fixed-size faces on a finer roughness grid:
// layer k holds r_k = ((IBL_ROUGH_LAYER_FIRST + k) / IBL_ROUGH_LAYER_GRID)^2, the Frostbite mapping on 21
// levels (steps of 0.05 in sqrt(r), 0.02-0.1 in r, finest where the LD changes fastest), k = 0..11: r =
// 0.2025 to 1, on faces of min(32, the chain's base face size). Measured on the seven shared HDRIs at 256 px
// against the exact LD (docs/accuracy.md "Rough layers"): 0.3-2.5% at r = 0.25-1 (2 x 2 design measurements
// before choosing: 16-px faces keep 4-28% at r = 0.2-0.3; a 0.1 step in r is 2-11% between layers at r <
// 0.5). The runtime reads the chain for r <= r_0, the layers for r >= r_1, and between them blends the two
// linearly in sqrt(r) (roughLayerWeight), so the lookup is continuous in r.
#define IBL_ROUGH_LAYER_GRID 20u
#define IBL_ROUGH_LAYER_FIRST 9u
#define IBL_ROUGH_LAYER_COUNT 12u
#define IBL_ROUGH_LAYER_MAX_FACE_SIZE 32u

// The perceptual roughness rough layer k holds (integers squared, then one division: the float nearest r_k,
// which files write as its short decimal).
IBL_FN float roughLayerRoughness(uint layer) {
    float k = IBL_FLOAT(IBL_ROUGH_LAYER_FIRST + layer);
    return k * k / IBL_FLOAT(IBL_ROUGH_LAYER_GRID * IBL_ROUGH_LAYER_GRID);
}

// The fractional layer that holds perceptual roughness r (clamped to [0, 1] first): negative below r_0.
IBL_FN float roughLayerForRoughness(float perceptualRoughness) {
    return sqrt(saturate(perceptualRoughness)) * IBL_FLOAT(IBL_ROUGH_LAYER_GRID) -
           IBL_FLOAT(IBL_ROUGH_LAYER_FIRST);
}

// The layers' share of a lookup at perceptual roughness r: 0 up to r_0, 1 from r_1 on, linear in sqrt(r)
// between.
IBL_FN float roughLayerWeight(float perceptualRoughness) {
    return saturate(roughLayerForRoughness(perceptualRoughness));
}

// The rough layers' face size for a chain whose level 0 has faces of baseFaceSize texels.
IBL_FN uint roughLayerFaceSize(uint baseFaceSize) {
    return baseFaceSize < IBL_ROUGH_LAYER_MAX_FACE_SIZE ? baseFaceSize : IBL_ROUGH_LAYER_MAX_FACE_SIZE;
}

IBL_END_NAMESPACE

#ifdef __cplusplus

namespace ibl {

enum class MipMapping : std::uint32_t {
    Frostbite = IBL_MIP_FROSTBITE,
    Linear = IBL_MIP_LINEAR,
    FilamentLod = IBL_MIP_FILAMENT_LOD,
};

// The names files, options and scene files use, in enum order.
inline constexpr std::array<const char*, 2> kMipMappingNames = {"frostbite", "linear"};

// The name files store for FilamentLod. Not a --mip-mapping choice: a chain that follows it also has its
// engine's level count (cube_profile.h engineLevelCount).
inline constexpr const char* kFilamentLodMappingName = "filament-lod";

inline const char* mipMappingName(MipMapping mapping) {
    return mapping == MipMapping::FilamentLod ? kFilamentLodMappingName
                                              : kMipMappingNames[std::size_t(mapping)];
}

// What the name means, for the human-readable key beside the stored name.
inline const char* mipMappingMeaning(MipMapping mapping) {
    if (mapping == MipMapping::FilamentLod) return "level m of L holds r = 1 - sqrt(1 - m/(L-1))";
    return mapping == MipMapping::Linear ? "level m of L holds r = m/(L-1)"
                                         : "level m of L holds r = (m/(L-1))^2";
}

// Exactly "frostbite" or "linear"; nullopt otherwise.
inline std::optional<MipMapping> mipMappingFromName(std::string_view name) {
    for (std::size_t i = 0; i < kMipMappingNames.size(); ++i)
        if (name == kMipMappingNames[i]) return MipMapping(i);
    return std::nullopt;
}

// A value read from a file: the name, or the prose of files written before the name was stored alone
// ("frostbite: level m of L holds perceptualRoughness (m/(L-1))^2"): the word before the first ':' or
// white space, in any case. nullopt for anything else.
inline std::optional<MipMapping> mipMappingFromStoredValue(std::string_view text) {
    std::string name;
    for (char ch : text) {
        if (ch == ':' || std::isspace(static_cast<unsigned char>(ch))) break;
        name += char(std::tolower(static_cast<unsigned char>(ch)));
    }
    if (name == kFilamentLodMappingName) return MipMapping::FilamentLod;
    return mipMappingFromName(name);
}

inline float perceptualRoughnessForLevel(int level, int levelCount, MipMapping mapping) {
    return mipLevelRoughness(std::uint32_t(mapping), std::uint32_t(level), std::uint32_t(levelCount));
}

inline constexpr const char* kRoughLayerRoughnessKey = "iblbake.roughLayerRoughness";

// The rough layers' roughness as files store it (KTX2 key kRoughLayerRoughnessKey: the shortest decimal of
// each r_k that reads back to the same float, space-separated; the manifest's
// products.specular.roughLayers.roughness: the same decimals as numbers).
inline std::string roughLayerRoughnessText() {
    std::string text;
    for (std::uint32_t k = 0; k < IBL_ROUGH_LAYER_COUNT; ++k) {
        char number[32];
        const std::to_chars_result end =
            std::to_chars(number, number + sizeof number, roughLayerRoughness(k));
        if (!text.empty()) text += ' ';
        text.append(number, end.ptr);
    }
    return text;
}

inline std::vector<double> roughLayerRoughnessValues() {
    std::vector<double> values;
    const std::string text = roughLayerRoughnessText();
    for (const char *at = text.data(), *end = text.data() + text.size(); at < end; ++at) {
        double value = 0.0;
        at = std::from_chars(at, end, value).ptr;
        values.push_back(value);
    }
    return values;
}

// What a reader does with them (the KTX2 key "iblbake.roughLayerMeaning", the manifest's "meaning").
inline const char* roughLayerMeaning() {
    return "layer k of 12 holds the LD of perceptual roughness r_k = ((9 + k) / 20)^2 on faces of "
           "min(32, the chain's base) texels; a lookup at r reads the chain up to r_0, the layers from r_1 "
           "(bilinear in a layer, linear in sqrt(r) between layers), and blends chain and layers linearly "
           "in sqrt(r) between r_0 and r_1";
}

inline int mipLevelCount(int faceSize) {
    return int(mipLevelCountForFaceSize(std::uint32_t(faceSize)));
}

} // namespace ibl

#endif

#endif
