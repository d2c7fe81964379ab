// The runtime stage of `iblbake accuracy`: material spheres shaded by the runtime module from a probe baked
// at each specular preset, against the brute-force renderer (Frostbite Appendix A) lit by the same input.
#include "sweep.h"

#include <iblbake/baker/dfg_lut.h>
#include <iblbake/baker/environment.h>
#include <iblbake/baker/irradiance.h>
#include <iblbake/baker/sh.h>
#include <iblbake/baker/specular.h>
#include <iblbake/baker/sun.h>
#include <iblbake/runtime/runtime.h>
#include <iblbake/runtime/runtime_reference.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <glm/geometric.hpp>

namespace ibl {

namespace {

const glm::vec3 kDielectricBase(0.8f, 0.55f, 0.35f);
const glm::vec3 kMetalBase(0.95f, 0.64f, 0.54f);

// A dielectric and a metal unit sphere of one roughness, seen by orthographic cameras from +Z and from
// above (grid x grid pixels each; pixels whose normal has NoV >= 0.15, where the split sum is meant to hold).
std::vector<ShadingPoint> spherePoints(float perceptualRoughness, int grid) {
    const glm::vec3 cameras[] = {glm::vec3(0, 0, 1), glm::normalize(glm::vec3(0.3f, 0.9f, 0.3f))};
    std::vector<ShadingPoint> points;
    for (float metallic : {0.0f, 1.0f})
        for (glm::vec3 c : cameras) {
            glm::vec3 right =
                glm::normalize(glm::cross(std::abs(c.y) < 0.9f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0), c));
            glm::vec3 up = glm::cross(c, right);
            for (int j = 0; j < grid; ++j)
                for (int i = 0; i < grid; ++i) {
                    float u = (i + 0.5f) / grid * 2 - 1, v = (j + 0.5f) / grid * 2 - 1;
                    float z2 = 1 - u * u - v * v;
                    if (z2 < 0.15f * 0.15f) continue;
                    glm::vec3 n = u * right + v * up + std::sqrt(z2) * c;
                    points.push_back(makeShadingPoint(n, n, c, metallic > 0 ? kMetalBase : kDielectricBase,
                                                      metallic, perceptualRoughness));
                }
        }
    return points;
}

// The probe the product ships, from `probeSource` (the residual of an extraction, or the full map when the
// sun stays in), at a specular quality: LD chain, DFG, SH, irradiance cube, and the disk light.
ProbeSet runtimeProbe(const CubeMap& probeSource, const CubeMap& full, const std::optional<SunDisk>& sun,
                      const SpecularSettings& settings, const Executor& executor,
                      CubeMapChain* chainOut = nullptr) {
    CubeMapChain chain = bakeSpecular(probeSource, settings, executor);
    const bool sunInLevel0 = sun && keepSunInLevel0(chain, full, Ktx2Format::RGBA32F);
    LdPyramid ld = ldPyramidFromChain(chain, MipMapping::Frostbite);
    ld.sunInLevel0 = sunInLevel0;
    ProbeSet set(std::move(ld), dfgTableFromImage(bakeDfgLut(DfgSettings{}, executor)),
                 shCoefficientsFrom(bakeDiffuseSH(probeSource, {}).irradiance, false));
    set.setIrradianceCube(bakeIrradianceCube(probeSource, IrradianceSettings{}, executor));
    if (sun) set.setSun(*sun);
    if (chainOut) *chainOut = std::move(chain);
    return set;
}

struct SphereColumns {
    std::vector<ShadingPoint> points;
    std::vector<std::size_t> start; // of each column, and the end
};

SphereColumns sphereColumns(const std::vector<float>& roughness, int grid) {
    SphereColumns c;
    for (float r : roughness) {
        c.start.push_back(c.points.size());
        std::vector<ShadingPoint> column = spherePoints(r, grid);
        c.points.insert(c.points.end(), column.begin(), column.end());
    }
    c.start.push_back(c.points.size());
    return c;
}

// Per column: sum |runtime - reference| / sum |reference| over its points and RGB (or, with `estimate`,
// sum estimate / sum |reference|: the reference's own error in the same measure).
std::vector<double> columnErrors(const SphereColumns& c, const ConvergedReference& reference,
                                 const std::vector<glm::vec4>* shaded) {
    std::vector<double> out;
    for (std::size_t k = 0; k + 1 < c.start.size(); ++k) {
        double err = 0.0, sum = 0.0;
        for (std::size_t i = c.start[k]; i < c.start[k + 1]; ++i) {
            const glm::dvec3 want = reference.results[i].total();
            for (int ch = 0; ch < 3; ++ch) {
                err +=
                    shaded ? std::abs(double((*shaded)[i][ch]) - want[ch]) : reference.errorEstimate[i][ch];
                sum += std::abs(want[ch]);
            }
        }
        out.push_back(sum > 0.0 ? err / sum : err);
    }
    return out;
}

std::string roughnessName(float r) {
    char name[32];
    std::snprintf(name, sizeof name, "r=%.1f", r);
    return name;
}

} // namespace

std::string sunInProbeWarning(double keptError, double perceptualRoughness, double extractedError) {
    char text[400];
    std::snprintf(
        text, sizeof text,
        "sun detected and left in the probe: runtime error %.1f%% at roughness %.1f on the sphere grid "
        "(%.1f%% with the sun extracted); extract it: iblbake --extract-sun, scene key extractSun",
        100.0 * keptError, perceptualRoughness, 100.0 * extractedError);
    return text;
}

SunInProbe measureSunInProbe(const CubeMap& source, const Executor& executor, int grid) {
    SunInProbe out;
    CubeMap residual = source;
    std::optional<SunDisk> sun;
    if (auto light = takeSunOut(residual, SunExtraction::IfDetected, SunDetectSettings{}))
        sun = sunDiskFrom(*light);
    if (!sun) return out;
    out.detected = true;
    for (int k = 0; k <= 10; ++k)
        out.roughness.push_back(float(k) / 10.0f);
    const SphereColumns c = sphereColumns(out.roughness, grid);
    const RuntimeOptions options;
    const ConvergedReference reference = renderConvergedReference(source, c.points, options);
    const SpecularSettings production;
    const std::vector<glm::vec4> kept =
        evaluateCpu(runtimeProbe(source, source, {}, production, executor), c.points, options);
    const std::vector<glm::vec4> extracted =
        evaluateCpu(runtimeProbe(residual, source, sun, production, executor), c.points, options);
    out.keptError = columnErrors(c, reference, &kept);
    out.extractedError = columnErrors(c, reference, &extracted);
    const std::size_t worst =
        std::size_t(std::max_element(out.keptError.begin(), out.keptError.end()) - out.keptError.begin());
    out.warning = sunInProbeWarning(out.keptError[worst], out.roughness[worst], out.extractedError[worst]);
    return out;
}

AccuracyStage measureRuntime(const SweepPlan& plan, const CubeMap& source, int repeats,
                             const Executor& executor) {
    const int size = source.faceSize;
    AccuracyStage stage;
    stage.name = "runtime";
    stage.title = "Runtime shading (per roughness)";
    stage.knobs = {"specularQuality", "sun"};
    stage.errorMetric = "mean over the roughness columns of the relative mean absolute error: sum |runtime - "
                        "reference| / sum |reference| over a column's points and RGB";
    stage.maxErrorMetric = "worst roughness column's relative mean absolute error";
    stage.energyErrorMetric = "|sum (runtime - reference)| / sum reference over every point and channel";
    stage.timeMeaning = "bakeSpecular of the probe's LD chain at the source face size (the only cost that "
                        "changes; DFG LUT at its defaults and the SH are shared)";

    // The product's setup, as `iblbake specular/diffuse --extract-sun` bake it: a detected sun is extracted
    // into the disk light, the residual goes to the probe (LD chain from level 1 on, SH, irradiance cube) and
    // level 0 keeps the sun's pixels. The reference is lit by the full map.
    CubeMap residual = source;
    std::optional<SunDisk> sun;
    if (auto light = takeSunOut(residual, SunExtraction::IfDetected, SunDetectSettings{}))
        sun = sunDiskFrom(*light);
    const SphereColumns c = sphereColumns(plan.runtimeRoughness, plan.runtimeGrid);
    const RuntimeOptions options;
    ConvergedReferenceSettings referenceSettings;
    referenceSettings.samples = 4096; // a few thousand points: affordable, and the estimate under 0.5%
    const ConvergedReference reference =
        renderConvergedReference(source, c.points, options, referenceSettings);
    const std::vector<double> own = columnErrors(c, reference, nullptr);
    for (std::size_t k = 0; k < own.size(); ++k)
        stage.referenceErrors.emplace_back(roughnessName(plan.runtimeRoughness[k]), own[k]);
    stage.reference =
        "renderConvergedReference (Frostbite Appendix A's integral; the " +
        std::to_string(reference.brightTexels) +
        " bright texels on an adaptive sub-texel grid, the rest by 2 x 2048 stratified samples per "
        "strategy; its own estimated error per column in referenceErrorEstimate) of " +
        std::to_string(c.points.size()) + " points on dielectric and metal spheres, lit by the full " +
        std::to_string(size) + " px environment; the probe: " +
        (sun ? "the residual (LD chain from level 1, irradiance cube) with the sun's pixels in "
               "level 0 and the extracted sun as a disk light"
             : "LD chain and irradiance cube (no sun detected)");

    auto measure = [&](MeasuredSetting& s, const std::vector<glm::vec4>& shaded) {
        const std::vector<double> columns = columnErrors(c, reference, &shaded);
        double signedError = 0.0, total = 0.0;
        for (std::size_t i = 0; i < c.points.size(); ++i)
            for (int ch = 0; ch < 3; ++ch) {
                signedError += double(shaded[i][ch]) - reference.results[i].total()[ch];
                total += reference.results[i].total()[ch];
            }
        for (std::size_t k = 0; k < columns.size(); ++k) {
            s.partErrors.emplace_back(roughnessName(plan.runtimeRoughness[k]), columns[k]);
            s.maxError = std::max(s.maxError, columns[k]);
            s.error += columns[k] / double(columns.size());
        }
        s.energyError = total > 0.0 ? std::abs(signedError) / total : std::abs(signedError);
    };
    for (Quality quality : {Quality::Draft, Quality::Production, Quality::Reference}) {
        SpecularSettings settings;
        settings.quality = quality;
        MeasuredSetting s;
        bakeSpecular(residual, settings, executor); // program build, untimed
        s.timesMs = timeRuns(repeats, [&] { bakeSpecular(residual, settings, executor); });
        s.timeMs = median(s.timesMs);
        s.label = std::string(qualityName(quality)) + " LD chain";
        s.knobs = {{"specularQuality", qualityName(quality)}, {"sun", sun ? "extracted" : "none"}};
        s.preset = qualityName(quality);
        measure(s, evaluateCpu(runtimeProbe(residual, source, sun, settings, executor), c.points, options));
        stage.settings.push_back(std::move(s));
    }
    if (sun) { // the same production bake with the sun left in the probe: what the warning measures
        const SpecularSettings production;
        MeasuredSetting s;
        s.timesMs = timeRuns(repeats, [&] { bakeSpecular(source, production, executor); });
        s.timeMs = median(s.timesMs);
        s.label = "production LD chain, sun left in the probe";
        s.knobs = {{"specularQuality", "production"}, {"sun", "kept"}};
        measure(s, evaluateCpu(runtimeProbe(source, source, {}, production, executor), c.points, options));
        const auto worst = std::max_element(s.partErrors.begin(), s.partErrors.end(),
                                            [](const auto& a, const auto& b) { return a.second < b.second; });
        const std::size_t k = std::size_t(worst - s.partErrors.begin());
        stage.warnings.push_back(sunInProbeWarning(worst->second, plan.runtimeRoughness[k],
                                                   stage.settings[1].partErrors[k].second));
        stage.settings.push_back(std::move(s));
    }
    markParetoFront(stage);
    return stage;
}

} // namespace ibl
