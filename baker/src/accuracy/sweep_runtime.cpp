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

} // namespace

AccuracyStage measureRuntime(const SweepPlan& plan, const CubeMap& source, int repeats,
                             const Executor& executor) {
    AccuracyStage stage;
    stage.name = "runtime";
    stage.title = "Runtime shading (per roughness)";
    stage.knobs = {"specularQuality"};
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
    const ReferenceLighting lighting = ReferenceLighting::distant(source);

    std::vector<ShadingPoint> points;
    std::vector<std::size_t> columnStart;
    for (float r : plan.runtimeRoughness) {
        columnStart.push_back(points.size());
        std::vector<ShadingPoint> column = spherePoints(r, plan.runtimeGrid);
        points.insert(points.end(), column.begin(), column.end());
    }
    columnStart.push_back(points.size());
    const RuntimeOptions options;
    ReferenceSettings referenceSettings;
    referenceSettings.samplesPerStrategy = plan.runtimeReferenceSamples;
    const std::vector<ReferenceResult> reference =
        renderReference(lighting, points, options, referenceSettings);
    stage.reference = "renderReference (Frostbite Appendix A, multiple importance sampling, " +
                      std::to_string(plan.runtimeReferenceSamples) + " samples per strategy) of " +
                      std::to_string(points.size()) + " points on dielectric and metal spheres, lit by the " +
                      "full environment; the probe: " +
                      (sun ? "the residual (LD chain from level 1, irradiance cube) with the sun's pixels in "
                             "level 0 and the extracted sun as a disk light"
                           : "LD chain and irradiance cube (no sun detected)");

    const DfgTable dfg = dfgTableFromImage(bakeDfgLut(DfgSettings{}, executor));
    const ShCoefficients sh = shCoefficientsFrom(bakeDiffuseSH(residual, {}).irradiance, false);
    const CubeMap irradiance = bakeIrradianceCube(residual, IrradianceSettings{}, executor);
    for (Quality quality : {Quality::Draft, Quality::Production, Quality::Reference}) {
        SpecularSettings settings;
        settings.quality = quality;
        CubeMapChain chain;
        MeasuredSetting s;
        bakeSpecular(residual, settings, executor); // program build, untimed
        s.timesMs = timeRuns(repeats, [&] { chain = bakeSpecular(residual, settings, executor); });
        s.timeMs = median(s.timesMs);
        s.label = std::string(qualityName(quality)) + " LD chain";
        s.knobs = {{"specularQuality", qualityName(quality)}};
        s.preset = qualityName(quality);
        const bool sunInLevel0 = sun && keepSunInLevel0(chain, source, Ktx2Format::RGBA32F);
        LdPyramid ld = ldPyramidFromChain(chain, MipMapping::Frostbite);
        ld.sunInLevel0 = sunInLevel0;
        ProbeSet set(std::move(ld), dfg, sh);
        set.setIrradianceCube(irradiance);
        if (sun) set.setSun(*sun);
        const std::vector<glm::vec4> shaded = evaluateCpu(set, points, options);
        double signedError = 0.0, total = 0.0, columnSum = 0.0;
        for (std::size_t k = 0; k + 1 < columnStart.size(); ++k) {
            double err = 0.0, sum = 0.0;
            for (std::size_t i = columnStart[k]; i < columnStart[k + 1]; ++i) {
                const glm::dvec3 want = reference[i].total();
                for (int c = 0; c < 3; ++c) {
                    err += std::abs(double(shaded[i][c]) - want[c]);
                    sum += std::abs(want[c]);
                    signedError += double(shaded[i][c]) - want[c];
                    total += want[c];
                }
            }
            const double columnError = sum > 0.0 ? err / sum : err;
            char name[32];
            std::snprintf(name, sizeof name, "r=%.1f", plan.runtimeRoughness[k]);
            s.partErrors.emplace_back(name, columnError);
            columnSum += columnError;
            s.maxError = std::max(s.maxError, columnError);
        }
        s.error = columnSum / double(plan.runtimeRoughness.size());
        s.energyError = total > 0.0 ? std::abs(signedError) / total : std::abs(signedError);
        stage.settings.push_back(std::move(s));
    }
    markParetoFront(stage);
    return stage;
}

} // namespace ibl
