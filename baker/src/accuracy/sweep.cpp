#include "sweep.h"

#include <iblbake/baker/dfg_lut.h>
#include <iblbake/baker/dfg_reference.h>
#include <iblbake/baker/error_metrics.h>
#include <iblbake/baker/irradiance.h>
#include <iblbake/baker/sh.h>
#include <iblbake/baker/specular.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <set>

namespace ibl {

SweepPlan SweepPlan::quick() {
    SweepPlan p;
    p.isQuick = true;
    p.sourceFaceSize = 16;
    p.dfgReferenceSize = 9;
    p.dfgReferenceSamples = 4096;
    p.dfgSizes = {8, 16, 32};
    p.dfgSamples = {16, 64, 256};
    p.specularSizes = {16};
    p.specularSamples = {16, 64, 256, 1024};
    p.specularBiases = {-0.5f, 0.0f};
    p.productionFaceSize = 32;
    p.productionTexelsPerLevel = 256;
    p.productionSamples = {32, 128, 512};
    p.irradianceFaceSize = 8;
    p.irradianceSamples = {32, 128, 512};
    p.runtimeRoughness = {0.0f, 0.5f, 1.0f};
    p.runtimeGrid = 3;
    return p;
}

std::vector<double> timeRuns(int repeats, const std::function<void()>& work) {
    std::vector<double> times;
    for (int i = 0; i < repeats; ++i) {
        auto start = std::chrono::steady_clock::now();
        work();
        times.push_back(
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
    }
    return times;
}

double median(std::vector<double> values) {
    std::sort(values.begin(), values.end());
    const std::size_t n = values.size();
    return n == 0 ? 0.0 : n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

AccuracyStage namedStage(std::string name, std::string title, std::vector<std::string> knobs) {
    AccuracyStage stage;
    stage.name = std::move(name);
    stage.title = std::move(title);
    stage.knobs = std::move(knobs);
    return stage;
}

namespace {

std::string format(const char* pattern, auto... values) {
    char text[512];
    std::snprintf(text, sizeof text, pattern, values...);
    return text;
}

// The preset sample counts of a stage (its Settings and samples-for function), from the library's presets,
// so that the sweep always contains them.
template <class Settings, class SamplesFor>
std::vector<std::pair<Quality, std::uint32_t>> presetSamples(SamplesFor samplesFor) {
    std::vector<std::pair<Quality, std::uint32_t>> out;
    for (Quality q : {Quality::Draft, Quality::Production, Quality::Reference}) {
        Settings s;
        s.quality = q;
        out.emplace_back(q, samplesFor(s));
    }
    return out;
}

std::vector<std::pair<Quality, std::uint32_t>> specularPresets() {
    return presetSamples<SpecularSettings>([](const SpecularSettings& s) { return samplesFor(s); });
}

std::vector<std::pair<Quality, std::uint32_t>> irradiancePresets() {
    return presetSamples<IrradianceSettings>(
        [](const IrradianceSettings& s) { return irradianceSamplesFor(s); });
}

// Levels m >= 1 of `chain` against reference(m): one part error per level, the worst level's figures.
template <class Reference>
void addLevelErrors(MeasuredSetting& s, const CubeMapChain& chain, MipMapping mapping, Reference reference) {
    const int levelCount = int(chain.levels.size());
    for (int m = 1; m < levelCount; ++m) {
        CubeErrors e = compareCubes(chain.levels[std::size_t(m)], reference(m));
        s.partErrors.emplace_back(
            format("L%d r=%.2f", m, perceptualRoughnessForLevel(m, levelCount, mapping)), e.relativeMeanAbs);
        s.error = std::max(s.error, e.relativeMeanAbs);
        s.maxError = std::max(s.maxError, e.maxRelativeToMean);
        s.energyError = std::max(s.energyError, e.energy);
    }
}

// The sweep's values plus the presets', ascending.
std::vector<std::uint32_t> withPresets(const std::vector<std::uint32_t>& sweep,
                                       const std::vector<std::pair<Quality, std::uint32_t>>& presets) {
    std::set<std::uint32_t> all(sweep.begin(), sweep.end());
    for (const auto& [quality, samples] : presets)
        all.insert(samples);
    return {all.begin(), all.end()};
}

std::string presetOf(std::uint32_t samples, const std::vector<std::pair<Quality, std::uint32_t>>& presets) {
    for (const auto& [quality, count] : presets)
        if (count == samples) return qualityName(quality);
    return "";
}

// Bilinear read of a LUT at (NoV, roughness) in [0, 1]^2 with texel centres at (i + 0.5) / N, clamped at the
// edges: how a renderer samples it.
glm::dvec3 sampleLut(const ImageRGBA& lut, double u, double v) {
    const int n = lut.width;
    const double x = std::clamp(u * n - 0.5, 0.0, n - 1.0), y = std::clamp(v * n - 0.5, 0.0, n - 1.0);
    const int x0 = std::min(int(x), n - 1), y0 = std::min(int(y), n - 1);
    const int x1 = std::min(x0 + 1, n - 1), y1 = std::min(y0 + 1, n - 1);
    const double fx = x - x0, fy = y - y0;
    auto at = [&](int i, int j) { return glm::dvec3(glm::vec3(lut.at(i, j))); };
    return (at(x0, y0) * (1 - fx) + at(x1, y0) * fx) * (1 - fy) +
           (at(x0, y1) * (1 - fx) + at(x1, y1) * fx) * fy;
}

} // namespace

AccuracyStage measureDfg(const SweepPlan& plan, int repeats, const Executor& executor) {
    AccuracyStage stage = namedStage("dfg", "DFG / diffuse LUT", {"size", "samples"});
    stage.reference =
        format("Frostbite Listing 18 in fp64 (iblbake/baker/dfg_reference.h), %u samples, at the "
               "centres of a %ux%u grid over (NoV, roughness); each LUT is read bilinearly "
               "there, as a renderer reads it",
               plan.dfgReferenceSamples, plan.dfgReferenceSize, plan.dfgReferenceSize);
    stage.errorMetric = "relative mean absolute error: sum |LUT - reference| / sum |reference| over the grid "
                        "and the three channels (DFG1, DFG2, Disney diffuse)";
    stage.maxErrorMetric = "largest absolute error of any grid point and channel (the LUT's values are 0..1)";
    stage.energyErrorMetric = "|sum (LUT - reference)| / sum reference over the grid and channels";
    stage.timeMeaning = "bakeDfgLut";
    const std::vector<glm::dvec3> reference =
        referenceDfgGrid(plan.dfgReferenceSize, plan.dfgReferenceSamples);
    const DfgSettings defaults;
    bakeDfgLut(DfgSettings{8, 16}, executor); // builds the OpenCL program outside the timed runs
    for (std::uint32_t size : plan.dfgSizes)
        for (std::uint32_t samples : plan.dfgSamples) {
            const DfgSettings settings{size, samples};
            MeasuredSetting s;
            const ImageRGBA lut = timedBake(s, repeats, [&] { return bakeDfgLut(settings, executor); });
            s.label = format("%u px, %u spp", size, samples);
            s.knobs = {{"size", std::to_string(size)}, {"samples", std::to_string(samples)}};
            if (size == defaults.size && samples == defaults.sampleCount) s.preset = "default";
            double absError = 0.0, absRef = 0.0, signedError = 0.0, sumRef = 0.0;
            const std::uint32_t g = plan.dfgReferenceSize;
            for (std::uint32_t k = 0; k < g * g; ++k) {
                glm::dvec3 got = sampleLut(lut, (k % g + 0.5) / g, (k / g + 0.5) / g), want = reference[k];
                for (int c = 0; c < 3; ++c) {
                    absError += std::abs(got[c] - want[c]);
                    absRef += std::abs(want[c]);
                    signedError += got[c] - want[c];
                    sumRef += want[c];
                    s.maxError = std::max(s.maxError, std::abs(got[c] - want[c]));
                }
            }
            s.error = absError / absRef;
            s.energyError = std::abs(signedError) / sumRef;
            stage.settings.push_back(std::move(s));
        }
    markParetoFront(stage);
    return stage;
}

AccuracyStage measureSpecular(const SweepPlan& plan, const CubeLoader& load, int repeats,
                              const Executor& executor) {
    AccuracyStage stage = namedStage("specular", "Specular LD chain", {"faceSize", "samples", "lodBias"});
    stage.reference =
        "referenceSpecularLevel: every source texel, solid-angle weighted, fp64, per level; bright texels "
        "over the output texel's footprint where the lobe is under a quarter texel wide";
    stage.errorMetric = "worst level's relative mean absolute error: max over levels m >= 1 of sum |level - "
                        "reference| / sum |reference| over texels and RGB";
    stage.maxErrorMetric = "largest |level - reference| of any texel and channel over that channel's mean "
                           "reference value, worst level";
    stage.energyErrorMetric =
        "|sum (level - reference) solid angle| / sum reference solid angle, worst level";
    stage.timeMeaning = "bakeSpecular (every level; the source cube is ingested once per face size, untimed)";
    const auto presets = specularPresets();
    const std::vector<std::uint32_t> samplesList = withPresets(plan.specularSamples, presets);
    const int presetSize = *std::max_element(plan.specularSizes.begin(), plan.specularSizes.end());
    const float presetBias = SpecularSettings{}.lodBias;
    bool warmed = false;
    for (int size : plan.specularSizes) {
        const CubeMap source = load(size);
        SpecularSettings base;
        const int levelCount = levelCountFor(size, base);
        std::vector<CubeMap> references;
        for (int m = 1; m < levelCount; ++m)
            references.push_back(referenceSpecularLevel(
                source, size >> m, perceptualRoughnessForLevel(m, levelCount, base.mapping)));
        if (!warmed) bakeSpecular(source, base, executor), warmed = true; // program build, untimed
        for (float bias : plan.specularBiases)
            for (std::uint32_t samples : samplesList) {
                const SpecularSettings settings{.samples = samples, .lodBias = bias};
                MeasuredSetting s;
                const CubeMapChain chain =
                    timedBake(s, repeats, [&] { return bakeSpecular(source, settings, executor); });
                s.label = format("%d px, %u spp, bias %+.1f", size, samples, bias);
                s.knobs = {{"faceSize", std::to_string(size)},
                           {"samples", std::to_string(samples)},
                           {"lodBias", format("%g", bias)}};
                if (size == presetSize && bias == presetBias) s.preset = presetOf(samples, presets);
                addLevelErrors(s, chain, settings.mapping,
                               [&](int m) -> const CubeMap& { return references[std::size_t(m - 1)]; });
                stage.settings.push_back(std::move(s));
            }
    }
    markParetoFront(stage);
    return stage;
}

namespace {

// Up to `count` texels of an n-texel cube, spread over it (all when it has no more).
std::vector<CubeTexel> texelSubset(int n, int count) {
    const std::size_t total = 6 * std::size_t(n) * n;
    std::vector<CubeTexel> out;
    auto texel = [&](std::size_t i) {
        return CubeTexel{int(i / (std::size_t(n) * n)), int(i % n), int(i / n % n)};
    };
    if (total <= std::size_t(count)) {
        for (std::size_t i = 0; i < total; ++i)
            out.push_back(texel(i));
        return out;
    }
    std::set<std::size_t> chosen; // golden-ratio steps: spread, deterministic
    for (std::size_t i = 0; chosen.size() < std::size_t(count); ++i)
        chosen.insert(std::size_t(std::fmod(double(i) * 0.6180339887498949, 1.0) * double(total)));
    for (std::size_t i : chosen)
        out.push_back(texel(i));
    return out;
}

} // namespace

AccuracyStage measureSpecularProduction(const SweepPlan& plan, const CubeMap& source, int repeats,
                                        const Executor& executor) {
    const int size = source.faceSize;
    AccuracyStage stage = namedStage("specular-production", format("Specular LD chain at %d px", size),
                                     {"faceSize", "samples"});
    stage.reference =
        format("referenceSpecularTexels (referenceSpecularLevel's integral: the source's bright "
               "texels weighted exactly, the rest by 2 x 2048 stratified GGX samples per texel, more on "
               "levels of fewer texels, up to 2 x 131072 on 1 x 1 faces) at up to %d "
               "texels of every level; its own estimated error per level in "
               "referenceErrorEstimate",
               plan.productionTexelsPerLevel);
    stage.errorMetric = "worst level's relative mean absolute error: max over levels m >= 1 of sum |level - "
                        "reference| / sum |reference| over the level's measured texels and RGB";
    stage.maxErrorMetric =
        "largest |level - reference| of any measured texel and channel over that channel's "
        "mean reference value, worst level";
    stage.energyErrorMetric =
        "|sum (level - reference)| / sum reference over the measured texels, worst level";
    stage.timeMeaning = "bakeSpecular (every level)";
    SpecularSettings base;
    const int levelCount = levelCountFor(size, base);
    std::vector<std::vector<CubeTexel>> texels(static_cast<std::size_t>(levelCount));
    std::vector<LdTexelReference> references(static_cast<std::size_t>(levelCount));
    for (int m = 1; m < levelCount; ++m) {
        const float r = perceptualRoughnessForLevel(m, levelCount, base.mapping);
        texels[std::size_t(m)] = texelSubset(size >> m, plan.productionTexelsPerLevel);
        references[std::size_t(m)] = referenceSpecularTexels(source, size >> m, r, texels[std::size_t(m)]);
        double estimate = 0.0, sum = 0.0;
        for (std::size_t k = 0; k < texels[std::size_t(m)].size(); ++k)
            for (int c = 0; c < 3; ++c)
                estimate += references[std::size_t(m)].errorEstimate[k][c],
                    sum += std::abs(references[std::size_t(m)].value[k][c]);
        stage.referenceErrors.emplace_back(format("L%d r=%.2f", m, r), sum > 0.0 ? estimate / sum : estimate);
    }
    const auto presets = specularPresets();
    bakeSpecular(source, base, executor); // program build, untimed
    for (std::uint32_t samples : withPresets(plan.productionSamples, presets)) {
        const SpecularSettings settings{.samples = samples};
        MeasuredSetting s;
        const CubeMapChain chain =
            timedBake(s, repeats, [&] { return bakeSpecular(source, settings, executor); });
        s.label = format("%d px, %u spp", size, samples);
        s.knobs = {{"faceSize", std::to_string(size)}, {"samples", std::to_string(samples)}};
        s.preset = presetOf(samples, presets);
        for (int m = 1; m < levelCount; ++m) {
            const std::vector<CubeTexel>& at = texels[std::size_t(m)];
            const LdTexelReference& want = references[std::size_t(m)];
            double absError = 0.0, absRef = 0.0, signedError = 0.0, sumRef = 0.0, channelRef[3] = {0, 0, 0},
                   channelMax[3] = {0, 0, 0};
            for (std::size_t k = 0; k < at.size(); ++k) {
                const glm::vec4 got = chain.levels[std::size_t(m)].faces[at[k].face].at(at[k].x, at[k].y);
                for (int c = 0; c < 3; ++c) {
                    const double d = double(got[c]) - want.value[k][c];
                    absError += std::abs(d), absRef += std::abs(want.value[k][c]);
                    signedError += d, sumRef += want.value[k][c];
                    channelRef[c] += std::abs(want.value[k][c]);
                    channelMax[c] = std::max(channelMax[c], std::abs(d));
                }
            }
            const double error = absRef > 0.0 ? absError / absRef : absError;
            s.partErrors.emplace_back(
                format("L%d r=%.2f", m, perceptualRoughnessForLevel(m, levelCount, base.mapping)), error);
            s.error = std::max(s.error, error);
            for (int c = 0; c < 3; ++c)
                if (channelRef[c] > 0.0)
                    s.maxError = std::max(s.maxError, channelMax[c] / (channelRef[c] / double(at.size())));
            s.energyError = std::max(s.energyError, sumRef > 0.0 ? std::abs(signedError) / sumRef : 0.0);
        }
        stage.settings.push_back(std::move(s));
    }
    markParetoFront(stage);
    return stage;
}

namespace {

// Radiance SH with the bands above `order` set to zero.
ShRgb truncated(ShRgb radiance, int order) {
    for (int i = (order + 1) * (order + 1); i < 9; ++i)
        radiance[std::size_t(i)] = glm::dvec3(0.0);
    return radiance;
}

const char* kCubeErrorMetric = "relative mean absolute error: sum |cube - reference| / sum |reference| over "
                               "texels and RGB";
const char* kCubeMaxMetric =
    "largest |cube - reference| of any texel and channel over that channel's mean reference value";
const char* kCubeEnergyMetric = "|sum (cube - reference) solid angle| / sum reference solid angle";

void setCubeErrors(MeasuredSetting& s, const CubeMap& cube, const CubeMap& reference) {
    CubeErrors e = compareCubes(cube, reference);
    s.error = e.relativeMeanAbs;
    s.maxError = e.maxRelativeToMean;
    s.energyError = e.energy;
}

} // namespace

std::vector<AccuracyStage> measureDiffuse(const SweepPlan& plan, const CubeMap& source, int repeats,
                                          const Executor& executor) {
    const int n = plan.irradianceFaceSize;
    const CubeMap reference = referenceIrradianceCube(source, n);
    const std::string referenceText =
        format("referenceIrradianceCube: every texel of the %d px source, "
               "L max(0, n.l) omega in fp64 at each texel of a %d px cube (E/pi)",
               source.faceSize, n);
    AccuracyStage sh = namedStage("sh", "SH irradiance (order x window)", {"order", "window"});
    sh.reference = referenceText;
    sh.errorMetric = std::string(kCubeErrorMetric) + " of the SH irradiance evaluated at the texel centres";
    sh.maxErrorMetric = kCubeMaxMetric;
    sh.energyErrorMetric = kCubeEnergyMetric;
    sh.timeMeaning = "bakeDiffuseSH (projection and window search)";
    struct ShCase {
        int order;
        ShWindowSettings window;
        std::string name;
    };
    std::vector<ShCase> cases;
    for (int order = 0; order <= 2; ++order)
        cases.push_back({order, {false, ShWindow::None, {}}, "none"});
    for (ShWindow w : {ShWindow::Sloan, ShWindow::Hanning, ShWindow::Lanczos})
        cases.push_back({2, {false, w, {}}, shWindowName(w)});
    cases.push_back({2, {}, "auto"});
    for (const ShCase& c : cases) {
        MeasuredSetting s;
        const DiffuseSH result = timedBake(s, repeats, [&] { return bakeDiffuseSH(source, c.window); });
        s.label = format("L%d, window %s", c.order, c.name.c_str());
        if (c.window.automatic && result.window.window != ShWindow::None)
            s.label += format(" (%s)", shWindowName(result.window.window));
        s.knobs = {{"order", std::to_string(c.order)}, {"window", c.name}};
        if (c.order == 2 && c.window.automatic) s.preset = "default";
        const ShRgb prescaled = prescaleIrradiance(truncated(result.radiance, c.order));
        setCubeErrors(s, irradianceCubeFromSH(prescaled, n), reference);
        sh.settings.push_back(std::move(s));
    }
    markParetoFront(sh);

    AccuracyStage cube = namedStage("irradiance", "Irradiance cube (samples)", {"samples"});
    cube.reference = referenceText;
    cube.errorMetric = kCubeErrorMetric;
    cube.maxErrorMetric = kCubeMaxMetric;
    cube.energyErrorMetric = kCubeEnergyMetric;
    cube.timeMeaning = "bakeIrradianceCube (sampled method)";
    const auto presets = irradiancePresets();
    IrradianceSettings warm;
    warm.faceSize = n;
    bakeIrradianceCube(source, warm, executor); // program build, untimed
    for (std::uint32_t samples : withPresets(plan.irradianceSamples, presets)) {
        const IrradianceSettings settings{.faceSize = n, .samples = samples};
        MeasuredSetting s;
        const CubeMap result =
            timedBake(s, repeats, [&] { return bakeIrradianceCube(source, settings, executor); });
        s.label = format("%u spp", samples);
        s.knobs = {{"samples", std::to_string(samples)}};
        s.preset = presetOf(samples, presets);
        setCubeErrors(s, result, reference);
        cube.settings.push_back(std::move(s));
    }
    markParetoFront(cube);
    return {sh, cube};
}

void markParetoFront(AccuracyStage& stage) {
    for (MeasuredSetting& a : stage.settings) {
        a.pareto = true;
        for (const MeasuredSetting& b : stage.settings)
            if (&a != &b && b.timeMs <= a.timeMs && b.error <= a.error &&
                (b.timeMs < a.timeMs || b.error < a.error)) {
                a.pareto = false;
                break;
            }
    }
}

} // namespace ibl
