#include "iblbake/baker/specular.h"
#include "iblbake/core/error.h"
#include "iblbake/core/numeric.h"
#include "iblbake/core/visibility.h"
#include "iblbake/opencl/dispatch.h"

#include "bright_split.h"
#include "ld_host_items.h"
#include "lobe_integral.h"

#include <ld.h>

#include <chrono>
#include <cmath>
#include <optional>

namespace ibl {
namespace {

static_assert(sizeof(CubePyramidLayout) == 8, "CubePyramidLayout must match cube_sample.h");
static_assert(sizeof(LdParams) == sizeof(CubePyramidLayout) + 28 &&
                  offsetof(LdParams, invLobeIntegral) == sizeof(CubePyramidLayout) + 20 &&
                  offsetof(LdParams, brightLaneStride) == sizeof(CubePyramidLayout) + 24,
              "LdParams must match ld.h");

struct LevelTable {
    std::vector<float> samples; // the samples above the horizon in ld.h's blocks (ldTableIndex)
    float invWeightSum = 0.0f;
    std::uint32_t count() const { return std::uint32_t(samples.size() / IBL_LD_SAMPLE_FLOATS); }
};

LevelTable levelTable(std::uint32_t n, float alpha, int sourceFaceSize, float lodBias, float maxLod) {
    const float omegaP = 4.0f * IBL_PI / (6.0f * float(sourceFaceSize) * float(sourceFaceSize));
    std::vector<LdSample> above;
    double weightSum = 0.0;
    for (std::uint32_t i = 0; i < n; ++i) {
        LdSample s = ldSampleEntry(i, n, alpha, omegaP, lodBias, maxLod);
        if (s.weight <= 0.0f) continue; // below the horizon: contributes nothing (Listing 19's NdotL > 0)
        above.push_back(s);
        weightSum += s.weight;
    }
    // Padding: straight along the normal with weight 0 (a finite read that adds 0).
    while (above.size() % IBL_LD_BLOCK != 0)
        above.push_back(LdSample{0.0f, 0.0f, 1.0f, 0.0f, 0.0f});
    LevelTable t;
    t.samples.resize(above.size() * IBL_LD_SAMPLE_FLOATS);
    for (std::uint32_t i = 0; i < above.size(); ++i) {
        const LdSample& s = above[i];
        const float components[IBL_LD_SAMPLE_FLOATS] = {s.x, s.y, s.z, s.weight, s.lod};
        for (std::uint32_t c = 0; c < IBL_LD_SAMPLE_FLOATS; ++c)
            t.samples[ldTableIndex(i, c)] = components[c];
    }
    t.invWeightSum = weightSum > 0.0 ? float(1.0 / weightSum) : 0.0f;
    return t;
}

// A lobe much narrower than a source texel needs few samples: they all land in one bilinear
// footprint. The GGX lobe of reflected directions covers about 4 pi alpha^2 sr (small alpha), a source
// texel 4 pi / (6 w^2), so the lobe spans 6 w^2 alpha^2 texels; we take 16 samples per texel it
// spans, at least 8 and at most the preset's count (beyond that, pre-filtered lookups cover the lobe).
std::uint32_t samplesForLobe(std::uint32_t maxSamples, float alpha, int sourceFaceSize) {
    double texelsSpanned = 6.0 * double(sourceFaceSize) * sourceFaceSize * double(alpha) * alpha;
    double wanted = std::ceil(16.0 * texelsSpanned);
    return std::uint32_t(
        std::clamp(wanted, double(std::min<std::uint32_t>(8, maxSamples)), double(maxSamples)));
}

} // namespace

MipMapping parseMipMapping(const std::string& name) {
    if (name == kFilamentLodMappingName) return MipMapping::FilamentLod; // a stage's, set by its profile
    if (std::optional<MipMapping> mapping = mipMappingFromName(name)) return *mapping;
    throw SettingError("mipMapping", quotedForMessage(name) + " is not one of frostbite, linear");
}

Quality parseQuality(const std::string& name) {
    if (name == "draft") return Quality::Draft;
    if (name == "production") return Quality::Production;
    if (name == "reference") return Quality::Reference;
    throw SettingError("quality", "'" + name + "' is not one of draft, production, reference");
}

const char* qualityName(Quality q) {
    return q == Quality::Draft ? "draft" : q == Quality::Reference ? "reference" : "production";
}

std::uint32_t samplesFor(const SpecularSettings& s) {
    if (s.samples > 0) return s.samples;
    switch (s.quality) {
    case Quality::Draft:
        return 32;
    case Quality::Reference:
        return 2048;
    default:
        return 256;
    }
}

namespace {

// Each texel the mean of the 2x2 it covers (faces of 1 texel stay as they are).
CubeMap downsampleBox(const CubeMap& level) {
    const int n = std::max(1, level.faceSize / 2);
    if (n == level.faceSize) return level;
    CubeMap out(n);
    for (int f = 0; f < 6; ++f)
        for (int y = 0; y < n; ++y)
            for (int x = 0; x < n; ++x)
                out.faces[f].at(x, y) =
                    0.25f * (level.faces[f].at(2 * x, 2 * y) + level.faces[f].at(2 * x + 1, 2 * y) +
                             level.faces[f].at(2 * x, 2 * y + 1) + level.faces[f].at(2 * x + 1, 2 * y + 1));
    return out;
}

} // namespace

int levelCountFor(int faceSize, const SpecularSettings& s) {
    const int full = mipLevelCount(faceSize);
    return s.levels > 0 ? std::min(s.levels, full) : full;
}

namespace {

void checkSpecularSource(const CubeMap& source) {
    if (!isPowerOfTwo(source.faceSize) || source.faceSize > 8192)
        throw Error("specular: face size " + std::to_string(source.faceSize) +
                    " is not a power of two up to 8192");
}

// What one LD bake of a source shares between its levels: the pyramid of its sampled residual and its
// bright texels (taken out of the residual), on the device (the CPU backend reads the host arrays, which it
// keeps).
class LdBake {
  public:
    LdBake(CubePyramid residualPyramid, BrightTexels bright, const SpecularSettings& settings,
           const Executor& executor)
        : settings_(settings), dispatcher_(executor), pyramid_(std::move(residualPyramid)),
          bright_(std::move(bright)), brightLanes_(brightEntryLanes(bright_)),
          pyramidData_(dispatcher_.share("specular source pyramid", pyramid_.data)),
          clustersData_(dispatcher_.upload("bright-texel clusters", bright_.clusters)),
          brightData_(dispatcher_.upload("bright texels", bright_.entries)),
          brightLanesData_(dispatcher_.upload("bright texels in lanes", brightLanes_)) {}
    // The residual is read only into the pyramid; the split is the argument, so it is released once the
    // pyramid is built and the levels' memory reuses its pages.
    LdBake(BrightSplit split, const SpecularSettings& settings, const Executor& executor)
        : LdBake(buildCubePyramid(split.residual), std::move(split.bright), settings, executor) {}
    LdBake(const LdBake&) = delete; // the host arrays point into its own pyramid and bright texels
    LdBake& operator=(const LdBake&) = delete;
    // A level still queued when an error unwinds may read the shared pyramid, which is freed next.
    ~LdBake() { dispatcher_.waitForDevice(); }

    // The LD of perceptual roughness r (N = V = R) on faces of n texels.
    CubeMap level(int n, float perceptualRoughness) const {
        return finishLevel(startLevel(n, perceptualRoughness));
    }
    // level() in two halves: on OpenCL, startLevel enqueues the kernels and the read and returns, so the
    // host can build the next level's table while the device runs this one.
    PendingDownload startLevel(int n, float perceptualRoughness) const {
        const float alpha = alphaFromPerceptual(perceptualRoughness);
        const int sourceFaceSize = int(pyramid_.layout.baseFaceSize);
        // Rough levels are small (a 16-texel face has 1/64 of the texels of a 128 one) and their wide
        // lobes want more samples, so faces under 32 texels get 32/n times the preset's count, up to 16x.
        const std::uint32_t levelSamples = samplesFor(settings_) * std::uint32_t(std::clamp(32 / n, 1, 16));
        LevelTable table =
            levelTable(samplesForLobe(levelSamples, alpha, sourceFaceSize), alpha, sourceFaceSize,
                       settings_.lodBias, float(pyramid_.layout.levelCount - 1));
        LdParams params{pyramid_.layout,
                        std::uint32_t(n),
                        table.count(),
                        table.invWeightSum,
                        bright_.clusterCount(),
                        alpha,
                        float(1.0 / lobeIntegral(alpha)),
                        brightLaneStride(bright_.count())};
        DispatchOutput out = dispatcher_.output(DispatchGrid::cube(std::uint32_t(n)));
        const DeviceArray<float> tableData = dispatcher_.upload("LD sample table", table.samples);
        if (std::uint32_t(n) <= IBL_LD_ONE_PASS_FACE_SIZE) {
            dispatcher_.run(kernel("ld.cl", "ldOnePass", ldOnePassItemHost), out, params, pyramidData_,
                            tableData, clustersData_, brightData_, brightLanesData_);
            return dispatcher_.startDownload(out);
        }
        dispatcher_.run(kernel("ld.cl", "ldLevel", ldLevelItemHost), out, params, pyramidData_, tableData);
        if (params.brightCount > 0)
            dispatcher_.run(kernel("ld.cl", "ldBright", ldBrightItemHost), out, params, clustersData_,
                            brightData_, brightLanesData_);
        return dispatcher_.startDownload(out);
    }
    CubeMap finishLevel(PendingDownload level) const { return dispatcher_.finishCube(std::move(level)); }
    // Whether startLevel returns before the level is done (OpenCL); on the CPU backend it runs the level.
    bool levelsOverlap() const { return dispatcher_.usesOpenCL(); }

  private:
    const SpecularSettings& settings_;
    const Dispatcher dispatcher_;
    const CubePyramid pyramid_;
    const BrightTexels bright_;
    const std::vector<float> brightLanes_; // bright_'s entries in lanes (bright_split.h)
    const DeviceArray<float> pyramidData_, clustersData_, brightData_, brightLanesData_;
};

// The chain of `source` from `bake` (its bright texels taken out; the residual is what is sampled). On
// OpenCL, level m + 1 is enqueued before level m is waited for, so that the device runs the levels back to
// back while the host builds the next table (on PoCL, each level waited ~0.1 ms from enqueue to read-back).
// A level's time is then from the previous level's end to its own, on both backends; on a CPU device the
// host thread that waits shares the cores with the next level's kernels, so the boundary between two
// levels' times can shift by a wake-up (docs/performance.md "LD chain per level").
CubeMapChain bakeChain(CubeMap source, const LdBake& bake, const SpecularSettings& settings,
                       std::vector<SpecularLevelTiming>* timings) {
    const int faceSize = source.faceSize;
    const int levelCount = levelCountFor(faceSize, settings);
    CubeMapChain chain;
    chain.levels.push_back(std::move(source)); // level 0: the mirror, unconvolved (Frostbite footnote 43)
    struct InFlight {
        int level;
        float perceptualRoughness;
        PendingDownload texels;
    };
    std::optional<InFlight> inFlight;
    auto previousEnd = std::chrono::steady_clock::now();
    const auto finish = [&] {
        chain.levels.push_back(bake.finishLevel(std::move(inFlight->texels)));
        const auto end = std::chrono::steady_clock::now();
        if (timings)
            timings->push_back({inFlight->level, inFlight->perceptualRoughness,
                                std::chrono::duration<double, std::milli>(end - previousEnd).count()});
        previousEnd = end;
        inFlight.reset();
    };
    for (int m = 1; m < levelCount; ++m) {
        if (settings.integratedLevels > 0 && m >= settings.integratedLevels) {
            if (inFlight) finish();
            chain.levels.push_back(downsampleBox(chain.levels.back()));
            continue;
        }
        const float r = settings.levelRoughness.empty()
                            ? perceptualRoughnessForLevel(m, levelCount, settings.mapping)
                            : settings.levelRoughness.at(std::size_t(m));
        InFlight next{m, r, bake.startLevel(std::max(1, faceSize >> m), r)};
        if (inFlight) finish();
        inFlight.emplace(std::move(next));
        if (!bake.levelsOverlap()) finish();
    }
    if (inFlight) finish();
    return chain;
}

CubeMapChain bakeSpecularSplit(CubeMap source, BrightSplit split, const SpecularSettings& settings,
                               const Executor& executor, std::vector<SpecularLevelTiming>* timings) {
    return bakeChain(std::move(source), LdBake(std::move(split), settings, executor), settings, timings);
}

// The rough layers of a source from `bake` (kernels/mip_mapping.h).
std::vector<CubeMap> bakeLayers(const CubeMap& source, const LdBake& bake) {
    const int faceSize = int(roughLayerFaceSize(std::uint32_t(source.faceSize)));
    std::vector<CubeMap> layers;
    for (std::uint32_t k = 0; k < IBL_ROUGH_LAYER_COUNT; ++k)
        layers.push_back(bake.level(faceSize, roughLayerRoughness(k)));
    return layers;
}

} // namespace

CubeMapChain bakeSpecular(CubeMap source, const SpecularSettings& settings, const Executor& executor,
                          std::vector<SpecularLevelTiming>* timings) {
    checkSpecularSource(source);
    // The residual is made in the source itself while its pyramid is built, then undone: no 6 MB copy of a
    // 256-px cube, whose pages each fault on first touch (the 1k sample on the CPU backend: 5,825 -> 4,964
    // page faults).
    const BrightChoice choice =
        chooseBrightTexels(source, settings.brightThreshold, settings.maxBrightTexels);
    CubePyramid residualPyramid;
    BrightTexels bright = withResidualInPlace(
        source, choice, [&](const CubeMap& residual) { residualPyramid = buildCubePyramid(residual); });
    const LdBake bake(std::move(residualPyramid), std::move(bright), settings, executor);
    return bakeChain(std::move(source), bake, settings, timings);
}

std::vector<CubeMap> bakeRoughLayers(const CubeMap& source, const SpecularSettings& settings,
                                     const Executor& executor) {
    checkSpecularSource(source);
    return bakeLayers(source,
                      LdBake(splitBrightTexels(source, settings.brightThreshold, settings.maxBrightTexels),
                             settings, executor));
}

SpecularWithRoughLayers bakeSpecularWithRoughLayers(const CubeMap& source, const SpecularSettings& settings,
                                                    const Executor& executor,
                                                    std::vector<SpecularLevelTiming>* timings) {
    checkSpecularSource(source);
    const LdBake bake(splitBrightTexels(source, settings.brightThreshold, settings.maxBrightTexels), settings,
                      executor);
    return {bakeChain(source, bake, settings, timings), bakeLayers(source, bake)};
}

VisibilityChain bakeSpecularWithVisibility(const CubeMap& premultiplied, const SpecularSettings& settings,
                                           const Executor& executor) {
    checkSpecularSource(premultiplied);
    VisibilityChain result;
    CubeMap source = premultiplied, visibility(premultiplied.faceSize);
    bool allVisible = true;
    for (int f = 0; f < 6; ++f)
        for (std::size_t i = 0; i < source.faces[f].pixels.size(); ++i) {
            glm::vec4& texel = source.faces[f].pixels[i];
            const VisibilityRepair repair = visibilityRepairOf(texel.w);
            result.clampedTexels += repair != VisibilityRepair::None;
            texel = repairedVisibilityTexel(texel, repair);
            allVisible = allVisible && texel.w == 1.0f;
            visibility.faces[f].pixels[i] = glm::vec4(texel.w, texel.w, texel.w, 1.0f);
        }
    // Visible everywhere: the capture is one without visibility, baked as such (the same bytes).
    if (allVisible) {
        result.chain = bakeSpecular(std::move(source), settings, executor);
        return result;
    }
    // The visibility is split at the colour's bright texels by the colour's factors, so that the sampled and
    // the exact paths weigh both alike.
    BrightChoice choice = chooseBrightTexels(source, settings.brightThreshold, settings.maxBrightTexels);
    result.chain = bakeSpecularSplit(source, applyBrightSplit(source, choice), settings, executor, nullptr);
    CubeMapChain visible =
        bakeSpecularSplit(visibility, applyBrightSplit(visibility, choice), settings, executor, nullptr);
    for (std::size_t m = 0; m < result.chain.levels.size(); ++m)
        for (int f = 0; f < 6; ++f)
            for (std::size_t i = 0; i < result.chain.levels[m].faces[f].pixels.size(); ++i)
                result.chain.levels[m].faces[f].pixels[i].w =
                    std::clamp(visible.levels[m].faces[f].pixels[i].x, 0.0f, 1.0f);
    result.hasVisibility = true;
    return result;
}

} // namespace ibl
