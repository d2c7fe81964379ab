// Probe data in the layout the kernels read: bordered LD pyramids, the 3-channel DFG table, local probes.
#include "iblbake/core/cube_pyramid.h"
#include "iblbake/core/error.h"
#include "iblbake/core/visibility.h"
#include "iblbake/runtime/runtime.h"

#include <algorithm>
#include <optional>

namespace ibl {

MipMapping parseStoredMipMapping(const std::string& text) {
    if (std::optional<MipMapping> mapping = mipMappingFromStoredValue(text)) return *mapping;
    throw Error("LD roughness mapping " + quotedForMessage(text) + " is neither frostbite nor linear");
}

LdPyramid ldPyramidFromChain(const CubeMapChain& chain, MipMapping mapping, ChainAlpha alpha) {
    if (chain.levels.empty()) throw Error("LD chain: no levels");
    const int base = chain.levels[0].faceSize;
    if (base <= 0 || (base & (base - 1)) != 0 || base > 8192)
        throw Error("LD chain: face size " + std::to_string(base) + " is not a power of two up to 8192");
    const int maxLevels = mipLevelCount(base);
    if (int(chain.levels.size()) > std::min(maxLevels, int(IBL_MAX_CUBE_LEVELS)))
        throw Error("LD chain: " + std::to_string(chain.levels.size()) + " levels for a base face of " +
                    std::to_string(base));
    LdPyramid pyramid;
    pyramid.mapping = mapping;
    pyramid.layout.baseFaceSize = uint32_t(base);
    pyramid.layout.levelCount = uint32_t(chain.levels.size());
    pyramid.data.assign(cubePyramidFloatCount(pyramid.layout), 0.0f);
    if (alpha == ChainAlpha::PremultipliedVisibility)
        pyramid.visibility.assign(cubePyramidTexelCount(pyramid.layout), 0.0f);
    for (uint32_t m = 0; m < pyramid.layout.levelCount; ++m) {
        const CubeMap& level = chain.levels[m];
        const int n = base >> m;
        if (level.faceSize != n)
            throw Error("LD chain: level " + std::to_string(m) + " has face size " +
                        std::to_string(level.faceSize) + ", expected " + std::to_string(n));
        for (const ImageRGBA& face : level.faces)
            if (face.width != n || face.height != n || face.pixels.size() != std::size_t(n) * std::size_t(n))
                throw Error("LD chain: level " + std::to_string(m) + " has a face that is not " +
                            std::to_string(n) + "x" + std::to_string(n));
        storeBorderedLevel(level, m, pyramid.layout, pyramid.data.data());
        if (alpha == ChainAlpha::PremultipliedVisibility)
            forEachBorderedTexel(level, m, pyramid.layout, [&](std::uint32_t o, const glm::vec4& v) {
                pyramid.visibility[o / 3u] = repairedVisibilityTexel(v).w;
            });
    }
    // Visible everywhere is no visibility: the probe then composes by its influence weight alone, with the
    // same operations (and bits) as a probe that never had one, where reading a pyramid of ones would give
    // bilinear sums of 1 - 2^-24 here and there.
    bool allVisible = true;
    if (alpha == ChainAlpha::PremultipliedVisibility)
        for (const CubeMap& level : chain.levels)
            for (const ImageRGBA& face : level.faces)
                for (const glm::vec4& v : face.pixels) {
                    pyramid.visibilityTexelsClamped += !(v.w >= 0.0f && v.w <= 1.0f);
                    allVisible = allVisible && v.w == 1.0f;
                }
    if (allVisible) pyramid.visibility.clear();
    return pyramid;
}

DfgTable dfgTableFromImage(const ImageRGBA& lut) {
    if (lut.width <= 0 || lut.width != lut.height ||
        lut.pixels.size() != std::size_t(lut.width) * std::size_t(lut.height))
        throw Error("DFG LUT: " + std::to_string(lut.width) + "x" + std::to_string(lut.height) +
                    " is not a non-empty square image");
    DfgTable table;
    table.size = uint32_t(lut.width);
    table.data.resize(3 * lut.pixels.size());
    for (std::size_t i = 0; i < lut.pixels.size(); ++i)
        for (int c = 0; c < 3; ++c)
            table.data[3 * i + std::size_t(c)] = lut.pixels[i][c];
    return table;
}

namespace {

ProbeVolume makeVolume(uint32_t shape, const glm::vec3& center, const glm::vec3& extent,
                       const glm::mat3& rotation) {
    ProbeVolume v{};
    v.shape = shape;
    v.center = center;
    v.axisX = rotation[0];
    v.axisY = rotation[1];
    v.axisZ = rotation[2];
    v.extent = extent;
    return v;
}

} // namespace

ProbeVolume sphereVolume(const glm::vec3& center, float radius, const glm::mat3& rotation) {
    return makeVolume(IBL_VOLUME_SPHERE, center, glm::vec3(radius, radius, radius), rotation);
}

ProbeVolume boxVolume(const glm::vec3& center, const glm::vec3& halfExtents, const glm::mat3& rotation) {
    return makeVolume(IBL_VOLUME_BOX, center, halfExtents, rotation);
}

float volumeSize(const ProbeVolume& v) {
    if (!volumeIsValid(v)) return 0.0f;
    if (v.shape == IBL_VOLUME_SPHERE) return 4.18879020478639f * v.extent.x * v.extent.x * v.extent.x;
    return 8.0f * v.extent.x * v.extent.y * v.extent.z;
}

ProbeSet::ProbeSet(LdPyramid distantLd, DfgTable dfg, ShCoefficients sh)
    : distant_(std::move(distantLd)), dfg_(std::move(dfg)), sh_(sh) {
    if (distant_.layout.levelCount == 0 || distant_.data.size() != cubePyramidFloatCount(distant_.layout))
        throw Error("probe set: the distant LD pyramid is empty or inconsistent with its layout");
    if (dfg_.size == 0 || dfg_.data.size() != 3 * std::size_t(dfg_.size) * dfg_.size)
        throw Error("probe set: the DFG table is empty or inconsistent with its size");
    if (!distant_.visibility.empty())
        throw Error(
            "probe set: the distant LD pyramid has a visibility; the distant probe is the background");
    distantData_ = distant_.data;
}

void ProbeSet::setIrradianceCube(const CubeMap& irradianceOverPi) {
    const int n = irradianceOverPi.faceSize;
    if (n <= 0 || n > 8192) throw Error("probe set: irradiance cube face size " + std::to_string(n));
    for (const ImageRGBA& face : irradianceOverPi.faces)
        if (face.width != n || face.height != n || face.pixels.size() != std::size_t(n) * std::size_t(n))
            throw Error("probe set: an irradiance cube face is not " + std::to_string(n) + "x" +
                        std::to_string(n));
    CubePyramidLayout layout{uint32_t(n), 1u};
    irradianceData_.assign(cubePyramidFloatCount(layout), 0.0f);
    storeBorderedLevel(irradianceOverPi, 0, layout, irradianceData_.data());
    irradianceLayout_ = layout;
    joinDistantData();
}

void ProbeSet::setRoughLayers(const std::vector<CubeMap>& layers) {
    const CubePyramidLayout one{roughLayerFaceSize(distant_.layout.baseFaceSize), 1u};
    const int n = int(one.baseFaceSize);
    if (layers.size() != IBL_ROUGH_LAYER_COUNT)
        throw Error("probe set: " + std::to_string(layers.size()) + " rough layers, expected " +
                    std::to_string(IBL_ROUGH_LAYER_COUNT));
    std::vector<float> data(layers.size() * cubePyramidFloatCount(one), 0.0f);
    for (std::size_t k = 0; k < layers.size(); ++k) {
        const bool square =
            std::all_of(layers[k].faces.begin(), layers[k].faces.end(), [&](const ImageRGBA& f) {
                return f.width == n && f.height == n && f.pixels.size() == std::size_t(n) * std::size_t(n);
            });
        if (layers[k].faceSize != n || !square)
            throw Error("probe set: rough layer " + std::to_string(k) + " is not " + std::to_string(n) + "x" +
                        std::to_string(n) + " per face");
        storeBorderedLevel(layers[k], 0, one, data.data() + k * cubePyramidFloatCount(one));
    }
    roughLayerData_ = std::move(data);
    joinDistantData();
}

RoughLayers ProbeSet::roughLayers() const {
    RoughLayers layers{};
    if (!roughLayerData_.empty()) {
        layers.faceSize = roughLayerFaceSize(distant_.layout.baseFaceSize);
        layers.layerCount = IBL_ROUGH_LAYER_COUNT;
    }
    layers.dataOffset = uint32_t(distant_.data.size() + irradianceData_.size());
    return layers;
}

void ProbeSet::joinDistantData() {
    if (distant_.data.size() + irradianceData_.size() + roughLayerData_.size() > std::size_t(UINT32_MAX))
        throw Error("probe set: distant data exceeds 2^32 floats");
    distantData_ = distant_.data;
    distantData_.insert(distantData_.end(), irradianceData_.begin(), irradianceData_.end());
    distantData_.insert(distantData_.end(), roughLayerData_.begin(), roughLayerData_.end());
}

std::size_t ProbeSet::addLocalProbe(const LocalProbeDesc& desc, const LdPyramid& ld) {
    if (ld.layout.levelCount == 0 || ld.data.size() != cubePyramidFloatCount(ld.layout))
        throw Error("probe set: a local LD pyramid is empty or inconsistent with its layout");
    if (!ld.visibility.empty() && ld.visibility.size() != ld.data.size() / 3u)
        throw Error("probe set: a local visibility pyramid is inconsistent with its LD layout");
    if (localData_.size() + ld.data.size() + ld.visibility.size() > std::size_t(UINT32_MAX))
        throw Error("probe set: local LD data exceeds 2^32 floats");
    LocalProbe p{};
    p.ld.shape = ld.layout;
    p.ld.dataOffset = uint32_t(localData_.size());
    p.ld.mapping = uint32_t(ld.mapping);
    p.proxy = desc.proxy;
    p.influence = desc.influence.value_or(desc.proxy);
    p.captureOffset = desc.captureOffset;
    p.fadeDistance = desc.fadeDistance;
    localData_.insert(localData_.end(), ld.data.begin(), ld.data.end());
    p.hasVisibility = ld.visibility.empty() ? 0u : 1u;
    p.visibilityOffset = p.hasVisibility != 0u ? uint32_t(localData_.size()) : 0u;
    localData_.insert(localData_.end(), ld.visibility.begin(), ld.visibility.end());
    // Smallest influence first; an invalid volume (size 0, weight 0 everywhere) sorts first and costs one
    // test. upper_bound keeps equal sizes in the order of addition.
    float size = volumeSize(p.influence);
    auto at = std::upper_bound(localSizes_.begin(), localSizes_.end(), size);
    std::size_t index = std::size_t(at - localSizes_.begin());
    localSizes_.insert(at, size);
    local_.insert(local_.begin() + std::ptrdiff_t(index), p);
    return index;
}

RuntimeParams makeRuntimeParams(const ProbeSet& set, const RuntimeOptions& o, std::size_t pointCount) {
    if (pointCount > std::size_t(UINT32_MAX)) throw Error("runtime: more than 2^32 shading points");
    RuntimeParams p{};
    uint32_t f = 0;
    if (o.specular) f |= IBL_RT_SPECULAR;
    if (o.diffuse) f |= IBL_RT_DIFFUSE;
    if (o.energyCompensation) f |= IBL_RT_ENERGY_COMPENSATION;
    if (o.diffuseModel == DiffuseModel::Disney) f |= IBL_RT_DISNEY_DIFFUSE;
    if (o.specularDominantDirection) f |= IBL_RT_SPECULAR_DOMINANT;
    if (o.specularTaps) f |= IBL_RT_SPECULAR_TAPS;
    if (o.diffuseDominantDirection) f |= IBL_RT_DIFFUSE_DOMINANT;
    if (o.specularOcclusion) f |= IBL_RT_SPECULAR_OCCLUSION;
    if (o.horizonOcclusion) f |= IBL_RT_HORIZON_OCCLUSION;
    if (o.distanceBasedRoughness) f |= IBL_RT_DISTANCE_ROUGHNESS;
    if (o.sun && set.sun()) f |= IBL_RT_SUN;
    if (o.sunEnergyNormalization) f |= IBL_RT_SUN_NORMALIZATION;
    if (o.sunQuadrature) f |= IBL_RT_SUN_QUADRATURE;
    if (set.distantLd().sunInLevel0) f |= IBL_RT_SUN_IN_LEVEL0;
    if (o.f90FromF0) f |= IBL_RT_F90_FROM_F0;
    if (set.sh().overPi) f |= IBL_RT_SH_OVER_PI;
    if (o.irradianceCube && set.hasIrradianceCube()) f |= IBL_RT_IRRADIANCE_CUBE;
    p.flags = f;
    p.dfgSize = set.dfg().size;
    p.localProbeCount = uint32_t(set.localProbes().size());
    p.pointCount = uint32_t(pointCount);
    p.distant.shape = set.distantLd().layout;
    p.distant.dataOffset = 0;
    p.distant.mapping = uint32_t(set.distantLd().mapping);
    if (set.sun()) p.sun = *set.sun();
    p.dielectricF0 = o.dielectricF0;
    p.irradiance.shape = set.irradianceLayout();
    p.irradiance.dataOffset = uint32_t(set.distantLd().data.size());
    p.distantRoughLayers = set.roughLayers();
    for (int i = 0; i < 9; ++i)
        for (int c = 0; c < 3; ++c)
            p.sh.c[3 * i + c] = set.sh().c[std::size_t(i)][c];
    return p;
}

} // namespace ibl
