// The specular LD chain (docs/conventions.md "Roughness and the LD chain"): level 0 is the unconvolved
// source, level m holds the GGX pre-integration (N = V = R) for the perceptual roughness the mip mapping
// gives it.
#pragma once

#include "iblbake/core/cube_pyramid.h"
#include "iblbake/core/cubemap.h"
#include "iblbake/ktx2/ktx2.h"
#include "iblbake/opencl/executor.h"

#include <mip_mapping.h>

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

namespace ibl {

// MipMapping, its names and perceptualRoughnessForLevel: kernels/mip_mapping.h.
// "frostbite" | "linear"; throws ibl::Error "'<name>' is not one of frostbite, linear" otherwise.
MipMapping parseMipMapping(const std::string& name);

enum class Quality { Draft, Production, Reference };
Quality parseQuality(const std::string& name);
const char* qualityName(Quality quality);

struct SpecularSettings {
    int levels = 0; // 0: down to 1x1 (log2(face size) + 1)
    MipMapping mapping = MipMapping::Frostbite;
    std::uint32_t samples = 0; // per texel and level; 0: from the quality preset
    Quality quality = Quality::Production;
    // Texels brighter than brightThreshold x the solid-angle-weighted mean luminance (at most
    // maxBrightTexels of them, the brightest) are integrated exactly instead of by sampling (ld.h). Only
    // studio_small_03 of the shared HDRIs has more than 256 at 256-px faces (its softboxes): a cap of 256
    // left them in the sampled residual, 6.4% off at level 2 and 2-5% at levels 1-7; 4096 brings every level
    // within 0.5% (level 8: 1.0%), for 3.7x that map's bake time; the others' bytes and times are unchanged.
    float brightThreshold = 32.0f;
    std::uint32_t maxBrightTexels = 4096;
    float lodBias =
        -0.5f; // added to Listing 19's 0.5 log2(omegaS / omegaP); measured best (docs/accuracy.md "Presets")
    // Levels from this one on are not integrated but box-downsampled from the level before (0: integrate
    // every level). A scene whose roughest material reads level m needs only m + 1 integrated levels; the
    // chain keeps its full length so that its roughness mapping stays the same (scene_plan.h).
    int integratedLevels = 0;
    // When set (one entry per level): level m >= 1 holds perceptual roughness levelRoughness[m] instead of
    // the mapping's, the roughness an engine profile's own lookup reads there (cube_profile.h
    // engineLevelRoughness; the glTF export's Babylon levels).
    std::vector<float> levelRoughness{};
};

std::uint32_t samplesFor(const SpecularSettings& settings);
int levelCountFor(int faceSize, const SpecularSettings& settings);
// Before any work: the face size a power of two up to limits::kMaxFaceSize, levels 0 (full) or 1 to the full
// count, samples up to limits::kMaxSamples. Throws ibl::SettingError "faceSize", "levels" or "samples".
void validateSpecularSettings(const SpecularSettings& settings, int faceSize);

// The backend that `auto` means for a process whose only bake is one LD chain (`iblbake specular`): the CPU
// backend for chains of at most kStandaloneCpuFaceSize texels a side at the production preset's samples or
// fewer, unless a device was named. Both backends run the same lane code (kernels/lanes.h); OpenCL's set-up
// before a first kernel costs more than such a chain takes on the CPU (the 1k sample's production chain at
// 256 px: the platform query alone, which loads PoCL and LLVM, 111-124 ms; the whole chain on this 2-core
// machine's CPU backend, 95 ms), so a device cannot win it back there. Larger or reference chains keep
// `auto`; a scene bake runs on its process's backend; explicit choices are kept.
inline constexpr int kStandaloneCpuFaceSize = 256;
Backend standaloneSpecularBackend(Backend requested, bool deviceNamed, const SpecularSettings& settings,
                                  int faceSize);

// A level's wall time from the previous level's end (the chain's start for the first) to its own end. On
// OpenCL the next level is enqueued before a level is read back, so this counts the device's time for the
// level and the host's work that did not overlap it.
struct SpecularLevelTiming {
    int level;
    float perceptualRoughness;
    double milliseconds;
};

// Bakes the chain from a source cube whose face size is the output's (a power of two). The source becomes
// level 0: a caller done with its cube moves it in instead of copying it.
CubeMapChain bakeSpecular(CubeMap source, const SpecularSettings& settings, const Executor& executor,
                          std::vector<SpecularLevelTiming>* timings = nullptr);

// The rough layers of the chain bakeSpecular bakes from `source` (kernels/mip_mapping.h IBL_ROUGH_LAYER_*):
// IBL_ROUGH_LAYER_COUNT cubes of roughLayerFaceSize(source.faceSize) texels, layer k the LD of
// roughLayerRoughness(k), integrated as the chain's levels are (the same settings, bright-texel split and
// sample tables for the face size). A runtime reads them instead of the chain's coarse levels
// (kernels/probe.h sampleLdWithLayers).
std::vector<CubeMap> bakeRoughLayers(const CubeMap& source, const SpecularSettings& settings,
                                     const Executor& executor);

// bakeSpecular and bakeRoughLayers of one source from one bright-texel split and one source pyramid (each
// alone builds them again: ~60 ms of CPU at 256-px faces); the same results as the two calls.
struct SpecularWithRoughLayers {
    CubeMapChain chain;
    std::vector<CubeMap> roughLayers;
};
SpecularWithRoughLayers bakeSpecularWithRoughLayers(const CubeMap& source, const SpecularSettings& settings,
                                                    const Executor& executor,
                                                    std::vector<SpecularLevelTiming>* timings = nullptr);

// A local probe's capture with its visibility (Frostbite 4.9.1.2: alpha 1 for the close surroundings, 0 for
// sky the composition fetches from farther probes), premultiplied: RGB = colour x visibility, A = the
// visibility (OpenEXR's associated alpha). The chain holds the same: each level's RGB is the LD of colour x
// visibility, its A the LD of the visibility, filtered with the same weights (one sample table per level,
// the visibility split at the colour's bright texels by the colour's factors), so LD / A is the average
// colour of the visible part of the lobe and a transparent texel adds nothing to its neighbours. Alpha NaN
// or < 0 makes a texel transparent (RGBA 0), > 1 is taken as 1 (colour kept); both counted. A capture that
// is visible everywhere is baked as bakeSpecular bakes it (hasVisibility false, the same bytes).
struct VisibilityChain {
    CubeMapChain chain;
    bool hasVisibility = false;
    std::size_t clampedTexels = 0;
};
VisibilityChain bakeSpecularWithVisibility(const CubeMap& premultiplied, const SpecularSettings& settings,
                                           const Executor& executor);

// Level 0 is the unconvolved source. A chain baked from the residual of a sun extraction gets the cube from
// before the extraction back as level 0 when `format` stores every texel of it unclamped: always, since a
// product is stored with a storage scale (products.h chooseProductStorage) that makes it fit; with
// clampToFormat (the user's explicit choice to clamp) only when no channel exceeds the format's range
// (16-bit and packed floats end near 65,000; a calibrated sun reaches ~1e9); never in BC6H, whose blocks
// blur the disk into the sky beside it. A mirror then reflects the
// sun's own pixels, and the runtime fades the disk light out where it reads level 0
// (LdPyramid::sunInLevel0, KTX2 key "iblbake.sunInLevel0"), so every roughness counts the sun once. Returns
// whether level 0 now holds the sun.
bool keepSunInLevel0(CubeMapChain& residualChain, const CubeMap& withSun, Ktx2Format format,
                     bool clampToFormat = false);

// Brute-force reference for one level: every source texel, solid-angle weighted, fp64 accumulation. Where
// the bake averages bright texels over an output texel's footprint (kernels/ld.h ldFootprintApplies: the
// lobe under a quarter texel wide), the reference does too: the source's bright texels (runtime_reference.h
// brightTexels) on a grid of 4 x 4 points per source texel inside the output texel, the rest at its centre.
CubeMap referenceSpecularLevel(const CubeMap& source, int outputFaceSize, float perceptualRoughness);

// The same integral at chosen texels of an output level, fast enough for production sizes (the accuracy
// report at 256 px): the source's bright texels (runtime_reference.h brightTexels) weighted exactly as
// referenceSpecularLevel weights them, the dim rest by stratified GGX samples in two independent halves of
// referenceSamplesPerHalf(texels.size()) each, normalized like it by the weights' sum (the bright ones' plus
// the dim samples' share).
// errorEstimate (per texel and channel): half the halves' difference plus the bright part's change at half
// the grids (the footprint's and each texel's).
struct CubeTexel {
    int face, x, y;
};
struct LdTexelReference {
    std::vector<glm::dvec3> value, errorEstimate;
};
LdTexelReference referenceSpecularTexels(const CubeMap& source, int outputFaceSize, float perceptualRoughness,
                                         std::span<const CubeTexel> texels);

// Samples per half for `texelCount` texels: 2048 from 1536 texels on, more for fewer texels so that a level
// costs about the same whatever its size (up to 2^17 per half): a level of 1 x 1 faces (6 texels) is the
// mean of only six values, whose own noise at 2048 read 0.76% on studio_small_03, as much as the error it
// judged.
std::uint32_t referenceSamplesPerHalf(std::size_t texelCount);

} // namespace ibl
