// The runtime probe-sampling module (docs/architecture.md; its conventions in docs/conventions.md): a set of
// baked probes and the evaluation of shading points against it on the CPU (TBB) or through OpenCL. The
// shading math is kernels/probe.h and kernels/parallax.h, shared by both paths. Links neither OpenImageIO nor
// OpenColorIO: engines and tools can use it without the baker.
//
// Radiance out = diffuse + specular of the standard material (Filament 4.8: f0 = 0.04 (1 - metallic) +
// baseColor metallic, diffuse colour = (1 - metallic) baseColor) lit by
//   - the distant probe: LD chain (split-sum specular) + DFG LUT + SH L2 irradiance (+ optional sun),
//   - local probes: LD chain + proxy (sphere or oriented box) + influence volume, specular only (Frostbite
//     4.9.3: local probes carry no diffuse), optionally a texel visibility (4.9.1.2), composed with the
//     distant probe by the 4.9.5 alpha rule (alpha = influence weight x visibility).
#pragma once

#include "iblbake/core/cubemap.h"
#include "iblbake/core/image.h"

#include <probe.h>

#include <array>
#include <filesystem>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

namespace ibl {

namespace ocl {
class Context;
}

// The mapping a file stores (KTX2 key "iblbake.roughnessMapping", the manifest's "roughnessMapping"): the
// name, or the prose written before the name was stored alone (mip_mapping.h mipMappingFromStoredValue);
// throws ibl::Error quoting the value otherwise.
MipMapping parseStoredMipMapping(const std::string& text);

// An LD chain as the kernels read it: the bordered pyramid of kernels/cube_sample.h built from the chain's
// own levels (not re-filtered), with its mapping.
struct LdPyramid {
    CubePyramidLayout layout{};
    MipMapping mapping = MipMapping::Frostbite;
    // Level 0 is the source with the extracted sun still in it (KTX2 key "iblbake.sunInLevel0" = "true";
    // kernels/probe.h IBL_RT_SUN_IN_LEVEL0): the sun's disk light then fades out where level 0 is read.
    bool sunInLevel0 = false;
    std::vector<float> data;
    // A local probe's texel visibility (Frostbite 4.9.1.2: 1 where the texel is the close surroundings, 0
    // where it is sky to be fetched from farther probes): empty for none (every texel visible), else a
    // scalar pyramid of `layout` (cubePyramidFloatCount(layout) / 3 floats, kernels/probe.h
    // cubeSampleLodScalar) in [0, 1], and `data` holds colour x visibility (premultiplied: the filtered
    // product is what a linear pre-filter of an RGBA capture gives without dividing, and a window texel
    // adds nothing to the wall colour beside it). A chain whose visibility is 1 at every texel gets none.
    std::vector<float> visibility;
    // Visibility texels that were NaN, negative or above 1 when the pyramid was built (stored as 0, 0, 1).
    std::size_t visibilityTexelsClamped = 0;
};

// How ldPyramidFromChain reads the chain's fourth channel.
enum class ChainAlpha {
    Ignore,                  // RGB is the colour; the pyramid has no visibility
    PremultipliedVisibility, // A is the visibility, RGB colour x visibility (what an alpha bake writes)
};

// Level m of the chain must have face size max(1, base >> m) with a power-of-two base (what bakeSpecular
// writes); the chain may stop before 1x1. Throws ibl::Error otherwise.
LdPyramid ldPyramidFromChain(const CubeMapChain& chain, MipMapping mapping = MipMapping::Frostbite,
                             ChainAlpha alpha = ChainAlpha::Ignore);

// The DFG LUT, 3 floats per texel (DFG1, DFG2, Disney), docs/conventions.md layout.
struct DfgTable {
    std::uint32_t size = 0;
    std::vector<float> data;
};
// From bakeDfgLut's image (square; R, G, B used). Throws ibl::Error for an empty or non-square image.
DfgTable dfgTableFromImage(const ImageRGBA& lut);

// Pre-scaled SH L2 irradiance coefficients, docs/conventions.md order: Filament's irradianceSH(n) = sum c_i
// p_i(n) returns the irradiance E(n), or E(n) / pi when overPi (cmgen's convention, Lambert's 1/pi folded
// in).
struct ShCoefficients {
    std::array<glm::vec3, 9> c{};
    bool overPi = false;
};

// From any 9 RGB coefficients in docs/conventions.md order, e.g. the baker's DiffuseSH::irradiance (overPi =
// false) or DiffuseSH::irradianceOverPi (overPi = true).
template <class Rgb9>
ShCoefficients shCoefficientsFrom(const Rgb9& coefficients, bool overPi) {
    ShCoefficients sh;
    for (std::size_t i = 0; i < 9; ++i)
        sh.c[i] = glm::vec3(coefficients[i]);
    sh.overPi = overPi;
    return sh;
}

// From any light with direction, angularRadius, color and illuminance members, e.g. the baker's DiskLight.
template <class Light>
SunDisk sunDiskFrom(const Light& light) {
    SunDisk sun;
    sun.direction = glm::vec3(light.direction);
    sun.angularRadius = float(light.angularRadius);
    sun.color = glm::vec3(light.color);
    sun.illuminance = float(light.illuminance);
    return sun;
}

// Loaders for the baker's KTX2 outputs (no OIIO: baker/src/io/ktx2_reader.cpp). The LD chain's mapping
// comes from its "iblbake.roughnessMapping" key (Frostbite when absent), sunInLevel0 from
// "iblbake.sunInLevel0". LD chains and irradiance cubes come back in radiance: their texels divided by
// the file's "iblbake.storageScale" (iblbake/ktx2/storage_scale.h; 1 when absent).
// A local probe's chain with a visibility has the key "iblbake.visibility" = "premultiplied-alpha": A is
// the visibility, RGB colour x visibility (ChainAlpha::PremultipliedVisibility), in an RGBA format. Files
// without the key (every bake before visibility existed) read as before; another value, or the key on a
// format without alpha, throws ibl::Error naming the file and the key.
inline constexpr const char* kVisibilityKey = "iblbake.visibility";
inline constexpr const char* kVisibilityPremultipliedAlpha = "premultiplied-alpha";
LdPyramid loadLdKtx2(const std::filesystem::path& path);
DfgTable loadDfgKtx2(const std::filesystem::path& path);
// The distant chain's rough layers (a scene bake's specular_rough.ktx2, docs/formats.md "Rough layers"), for
// ProbeSet::setRoughLayers: a cube map array of IBL_ROUGH_LAYER_COUNT layers whose key
// kRoughLayerRoughnessKey names this runtime's grid (kernels/mip_mapping.h); throws ibl::Error naming
// the file otherwise.
std::vector<CubeMap> loadRoughLayersKtx2(const std::filesystem::path& path);
// The baker's irradiance cube (`iblbake diffuse --irradiance-cube`: one level of E / pi).
CubeMap loadIrradianceKtx2(const std::filesystem::path& path);

// Volumes: `rotation` columns are the volume's local axes in world space (orthonormal).
ProbeVolume sphereVolume(const glm::vec3& center, float radius, const glm::mat3& rotation = glm::mat3(1.0f));
ProbeVolume boxVolume(const glm::vec3& center, const glm::vec3& halfExtents,
                      const glm::mat3& rotation = glm::mat3(1.0f));
float volumeSize(const ProbeVolume& volume); // m^3; 0 for an invalid volume

struct LocalProbeDesc {
    ProbeVolume proxy{};                  // parallax geometry
    std::optional<ProbeVolume> influence; // where the probe applies (default: the proxy)
    glm::vec3 captureOffset{0.0f};        // capture point = proxy centre + offset along its axes
    float fadeDistance = 0.0f;            // soft transition inside the influence boundary (m)
};

class ProbeSet {
  public:
    // The distant probe is the background of the composition: a distant pyramid with a visibility throws.
    ProbeSet(LdPyramid distantLd, DfgTable dfg, ShCoefficients sh);

    // Diffuse from an irradiance cube holding E / pi (what `iblbake diffuse --irradiance-cube` writes)
    // instead of the SH: bilinear, so it keeps what L2 SH cannot (compact lights' irradiance; no ringing).
    // Any face size >= 1. Throws ibl::Error for an empty or inconsistent cube.
    void setIrradianceCube(const CubeMap& irradianceOverPi);
    bool hasIrradianceCube() const { return irradianceLayout_.levelCount != 0; }

    // The distant chain's rough layers (kernels/mip_mapping.h IBL_ROUGH_LAYER_*; the baker's bakeRoughLayers
    // of the source the chain's levels 1+ come from): IBL_ROUGH_LAYER_COUNT cubes of
    // roughLayerFaceSize(the chain's base face size) texels. Lookups from r_0 on then blend into them
    // (kernels/probe.h sampleLdWithLayers). Throws ibl::Error for another count or face size.
    void setRoughLayers(const std::vector<CubeMap>& layers);
    RoughLayers roughLayers() const; // layerCount 0 when none; dataOffset into distantData()

    void setSun(const SunDisk& sun) { sun_ = sun; }
    void clearSun() { sun_.reset(); }
    const std::optional<SunDisk>& sun() const { return sun_; }

    // Adds a local probe whose LD chain was captured at the desc's capture point (in world orientation),
    // with the chain's visibility if it has one. Probes are evaluated from the smallest influence volume to
    // the largest (Frostbite 4.9.5: "from small to big volumes"); equal sizes keep the order of addition.
    // Returns the probe's evaluation index at the time of the call.
    std::size_t addLocalProbe(const LocalProbeDesc& desc, const LdPyramid& ld);

    const LdPyramid& distantLd() const { return distant_; }
    // What the kernels read as the distant buffer: the LD pyramid, then the irradiance cube and the rough
    // layers if set.
    const std::vector<float>& distantData() const { return distantData_; }
    const CubePyramidLayout& irradianceLayout() const { return irradianceLayout_; }
    const DfgTable& dfg() const { return dfg_; }
    const ShCoefficients& sh() const { return sh_; }
    const std::vector<LocalProbe>& localProbes() const { return local_; } // evaluation order
    const std::vector<float>& localLdData() const { return localData_; }  // local pyramids, visibilities

  private:
    void joinDistantData();

    LdPyramid distant_;
    std::vector<float> distantData_;
    CubePyramidLayout irradianceLayout_{};
    std::vector<float> irradianceData_;
    std::vector<float> roughLayerData_; // empty: no rough layers
    DfgTable dfg_;
    ShCoefficients sh_;
    std::optional<SunDisk> sun_;
    std::vector<LocalProbe> local_;
    std::vector<float> localSizes_;
    std::vector<float> localData_;
};

enum class DiffuseModel { Lambert, Disney };

struct RuntimeOptions {
    bool specular = true;
    bool diffuse = true;
    bool energyCompensation = true;                    // Filament 4.7.2
    DiffuseModel diffuseModel = DiffuseModel::Lambert; // Disney: times the LUT's B (Listing 24)
    bool specularDominantDirection = true;             // probe.h's specularDominantDirection
    bool diffuseDominantDirection = false;             // Listing 23
    bool specularOcclusion = true;                     // Listing 26 (no effect at ao = 1)
    bool horizonOcclusion = true;                      // Filament 5.6.2.1 (no effect when r.n >= 0)
    bool distanceBasedRoughness = true;                // Listing 25
    bool sun = true;                                   // when the set has one
    bool irradianceCube = true; // diffuse from the set's irradiance cube when it has one (else the SH)
    // The sun's specular: integrated over the disk (16 points, kernels/probe.h sunSpecularQuadrature), or
    // with false Listing 6's representative point, normalized by (alpha / alpha')^2 with
    // sunEnergyNormalization, else as printed (too bright at low roughness).
    bool sunQuadrature = true;
    bool sunEnergyNormalization = true;
    // The distant probe's LD from the fitted taps (kernels/specular_taps.h), else one read in the dominant
    // direction (the split sum's lookup).
    bool specularTaps = false;
    bool f90FromF0 = false; // Filament 5.6.2 pre-baked specular occlusion; else f90 = 1
    float dielectricF0 = 0.04f;
};

// The kernel arguments for a set and options (for callers of kernels/probe.h's shadePoint directly).
RuntimeParams makeRuntimeParams(const ProbeSet& set, const RuntimeOptions& options, std::size_t pointCount);

// CPU (TBB): RGB radiance and the local probes' composed alpha per point.
std::vector<glm::vec4> evaluateCpu(const ProbeSet& set, std::span<const ShadingPoint> points,
                                   const RuntimeOptions& options = {});
// The same, split into diffuse and specular (for tests and tools).
std::vector<ShadeResult> shadeCpu(const ProbeSet& set, std::span<const ShadingPoint> points,
                                  const RuntimeOptions& options = {});

// OpenCL: uploads the set once; each evaluate() uploads the points and runs kernels/runtime.cl. The
// context must outlive the evaluator. Throws ibl::Error on any CL failure.
class OpenCLProbeEvaluator {
  public:
    OpenCLProbeEvaluator(ocl::Context& context, const ProbeSet& set);
    ~OpenCLProbeEvaluator();
    OpenCLProbeEvaluator(const OpenCLProbeEvaluator&) = delete;
    OpenCLProbeEvaluator& operator=(const OpenCLProbeEvaluator&) = delete;

    std::vector<glm::vec4> evaluate(std::span<const ShadingPoint> points, const RuntimeOptions& options = {});
    double lastKernelMilliseconds() const { return lastKernelMs_; }

  private:
    struct Buffers;
    ocl::Context& context_;
    const ProbeSet& set_;
    std::unique_ptr<Buffers> buffers_;
    double lastKernelMs_ = 0.0;
};

// Convenience: a point of the standard material.
inline ShadingPoint makeShadingPoint(const glm::vec3& position, const glm::vec3& normal,
                                     const glm::vec3& view, const glm::vec3& baseColor, float metallic,
                                     float perceptualRoughness, float ao = 1.0f) {
    ShadingPoint p;
    p.position = position;
    p.normal = normal;
    p.view = view;
    p.baseColor = baseColor;
    p.metallic = metallic;
    p.perceptualRoughness = perceptualRoughness;
    p.ao = ao;
    return p;
}

} // namespace ibl
