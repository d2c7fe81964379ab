// The runtime stage of `iblbake accuracy`: material spheres shaded by the runtime module from a probe baked
// at each specular preset, against the brute-force renderer (Frostbite Appendix A) lit by the same input.
#include "sweep.h"

#include <iblbake/baker/dfg_lut.h>
#include <iblbake/baker/environment.h>
#include <iblbake/baker/specular.h>
#include <iblbake/baker/sphere_columns.h>
#include <iblbake/baker/sun.h>
#include <iblbake/baker/sun_in_probe.h>
#include <iblbake/runtime/runtime.h>
#include <iblbake/runtime/runtime_reference.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace ibl {

namespace {

// The index of the worst roughness column of a measured setting.
std::size_t worstColumn(const MeasuredSetting& s) {
    return std::size_t(std::max_element(s.partErrors.begin(), s.partErrors.end(),
                                        [](const auto& a, const auto& b) { return a.second < b.second; }) -
                       s.partErrors.begin());
}

std::string roughnessName(float r) {
    char name[32];
    std::snprintf(name, sizeof name, "r=%.1f", r);
    return name;
}

} // namespace

AccuracyStage measureRuntime(const SweepPlan& plan, const CubeMap& source, int repeats,
                             const Executor& executor) {
    const int size = source.faceSize;
    AccuracyStage stage =
        namedStage("runtime", "Runtime shading (per roughness)", {"specularQuality", "sun", "lookup"});
    stage.errorMetric = "mean over the roughness columns of the relative mean absolute error: sum |runtime - "
                        "reference| / sum |reference| over a column's points and RGB";
    stage.maxErrorMetric = "worst roughness column's relative mean absolute error";
    stage.energyErrorMetric = "|sum (runtime - reference)| / sum reference over every point and channel";
    stage.timeMeaning =
        "bakeSpecularWithRoughLayers: the probe's LD chain and its rough layers at the source face size (the "
        "only cost that changes; DFG LUT at its defaults and the SH are shared)";

    // The product's setup, as `iblbake specular/diffuse --extract-sun` bake it: a detected sun is extracted
    // into the disk light, the residual goes to the probe (LD chain from level 1 on, SH, irradiance cube) and
    // level 0 keeps the sun's pixels. The reference is lit by the full map.
    CubeMap residual = source;
    std::optional<SunDisk> sun;
    if (auto light = takeSunOut(residual, SunExtraction::IfDetected, SunDetectSettings{}))
        sun = sunDiskFrom(*light);
    // Without a sun, a compact light the detector rejects by size (sun_in_probe.h): the report adds the
    // production probe with it extracted, which `--sun-max-solid-angle` bakes.
    CubeMap compactResidual = source;
    std::optional<DiskLight> compactLight;
    if (!sun) compactLight = takeCompactLightOut(compactResidual);
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
        (sun ? "the residual (LD chain from level 1, its rough layers, irradiance cube) with the sun's "
               "pixels in "
               "level 0 and the extracted sun as a disk light"
             : "LD chain, its rough layers and irradiance cube (no sun detected)");

    const DfgTable dfg = dfgTableFromImage(bakeDfgLut(DfgSettings{}, executor));
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
    std::optional<ProbeSet> productionProbe;
    for (Quality quality : {Quality::Draft, Quality::Production, Quality::Reference}) {
        SpecularSettings settings;
        settings.quality = quality;
        MeasuredSetting s;
        bakeSpecularWithRoughLayers(residual, settings, executor); // program build, untimed
        s.timesMs = timeRuns(repeats, [&] { bakeSpecularWithRoughLayers(residual, settings, executor); });
        s.timeMs = median(s.timesMs);
        s.label = std::string(qualityName(quality)) + " LD chain";
        s.knobs = {{"specularQuality", qualityName(quality)},
                   {"sun", sun ? "extracted" : "none"},
                   {"lookup", "single"}};
        s.preset = qualityName(quality);
        ProbeSet probe = shippedProbe(residual, source, sun, settings, dfg, executor);
        measure(s, evaluateCpu(probe, c.points, options));
        if (quality == Quality::Production) productionProbe = std::move(probe);
        stage.settings.push_back(std::move(s));
    }
    if (sun) { // the same production bake with the sun left in the probe: what the warning measures
        const SpecularSettings production;
        MeasuredSetting s;
        s.timesMs = timeRuns(repeats, [&] { bakeSpecularWithRoughLayers(source, production, executor); });
        s.timeMs = median(s.timesMs);
        s.label = "production LD chain, sun left in the probe";
        s.knobs = {{"specularQuality", "production"}, {"sun", "kept"}, {"lookup", "single"}};
        measure(s,
                evaluateCpu(shippedProbe(source, source, {}, production, dfg, executor), c.points, options));
        const std::size_t k = worstColumn(s);
        stage.warnings.push_back(sunInProbeWarning(s.partErrors[k].second, plan.runtimeRoughness[k],
                                                   stage.settings[1].partErrors[k].second));
        stage.settings.push_back(std::move(s));
    }
    if (compactLight) { // the production bake with the compact light extracted as the disk
        const SpecularSettings production;
        MeasuredSetting s;
        s.timesMs =
            timeRuns(repeats, [&] { bakeSpecularWithRoughLayers(compactResidual, production, executor); });
        s.timeMs = median(s.timesMs);
        char label[160];
        std::snprintf(label, sizeof label,
                      "production LD chain, compact light (disk of %.1f degrees) extracted "
                      "(--sun-max-solid-angle %g)",
                      compactLight->angularRadiusDegrees(), kCompactLightMaxSolidAngle);
        s.label = label;
        s.knobs = {
            {"specularQuality", "production"}, {"sun", "compact light extracted"}, {"lookup", "single"}};
        productionProbe =
            shippedProbe(compactResidual, source, sunDiskFrom(*compactLight), production, dfg, executor);
        measure(s, evaluateCpu(*productionProbe, c.points, options));
        const MeasuredSetting& kept = stage.settings[1]; // production, the light in the probe
        const std::size_t k = worstColumn(kept);
        stage.warnings.push_back(
            compactLightInProbeWarning(compactLight->angularRadiusDegrees(), kept.partErrors[k].second,
                                       plan.runtimeRoughness[k], s.partErrors[k].second));
        stage.settings.push_back(std::move(s));
    }
    { // the shipped production probe (a compact light extracted where there is one) read through the fitted
      // taps (RuntimeOptions::specularTaps, materials.specularLookup "taps"), against the same reference
        MeasuredSetting s = stage.settings[compactLight ? stage.settings.size() - 1 : 1];
        s.label += ", fitted taps";
        s.knobs.back() = {"lookup", "taps"};
        s.preset.clear();
        s.partErrors.clear();
        s.error = s.maxError = 0.0;
        RuntimeOptions taps = options;
        taps.specularTaps = true;
        measure(s, evaluateCpu(*productionProbe, c.points, taps));
        stage.settings.push_back(std::move(s));
    }
    markParetoFront(stage);
    return stage;
}

} // namespace ibl
