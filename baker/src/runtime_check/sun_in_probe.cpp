// What a sun left in the probe costs at runtime (sun_in_probe.h).
#include "iblbake/baker/sun_in_probe.h"

#include "iblbake/baker/dfg_lut.h"
#include "iblbake/baker/environment.h"
#include "iblbake/baker/sphere_columns.h"
#include "iblbake/core/cube_pyramid.h"
#include "iblbake/runtime/runtime.h"

#include <algorithm>
#include <cstdio>

namespace ibl {

std::string sunInProbeWarning(double keptError, double perceptualRoughness, double extractedError) {
    char text[400];
    std::snprintf(
        text, sizeof text,
        "sun detected and left in the probe: runtime error %.1f%% at roughness %.1f on the sphere grid "
        "(%.1f%% with the sun extracted); extract it: iblbake --extract-sun, scene key "
        "environment.extractSun",
        100.0 * keptError, perceptualRoughness, 100.0 * extractedError);
    return text;
}

std::string compactLightInProbeWarning(double angularRadiusDegrees, double keptError,
                                       double perceptualRoughness, double extractedError) {
    char text[400];
    std::snprintf(text, sizeof text,
                  "compact light (disk of %.1f degrees) left in the probe: runtime error %.1f%% at roughness "
                  "%.1f on the sphere grid (%.1f%% with it extracted as a disk light); extract it: iblbake "
                  "--extract-sun --sun-max-solid-angle %g, scene keys environment.extractSun and "
                  "environment.sunMaxSolidAngle",
                  angularRadiusDegrees, 100.0 * keptError, perceptualRoughness, 100.0 * extractedError,
                  kCompactLightMaxSolidAngle);
    return text;
}

std::optional<DiskLight> takeCompactLightOut(CubeMap& cube, SunDetectSettings detection) {
    detection.maxSolidAngle = kCompactLightMaxSolidAngle;
    return takeSunOut(cube, SunExtraction::IfDetected, detection);
}

SunInProbe measureSunInProbe(const CubeMap& environment, const Executor& executor, int grid,
                             const SunDetectSettings& detection) {
    SunInProbe out;
    CubeMap source = environment;
    while (source.faceSize > kSunInProbeFaceSize)
        source = downsampleCube(source);
    CubeMap residual = source;
    std::optional<DiskLight> light = takeSunOut(residual, SunExtraction::IfDetected, detection);
    if (!light && detection.maxSolidAngle < kCompactLightMaxSolidAngle) {
        light = takeCompactLightOut(residual, detection);
        out.compactLight = light.has_value();
    }
    if (!light) return out;
    const std::optional<SunDisk> sun = sunDiskFrom(*light);
    out.detected = true;
    out.angularRadiusDegrees = light->angularRadiusDegrees();
    for (int k = 0; k <= 10; ++k)
        out.roughness.push_back(float(k) / 10.0f);
    const SphereColumns c = sphereColumns(out.roughness, grid);
    const RuntimeOptions options;
    const ConvergedReference reference = renderConvergedReference(source, c.points, options);
    const SpecularSettings production;
    const DfgTable dfg = dfgTableFromImage(bakeDfgLut(DfgSettings{}, executor));
    const std::vector<glm::vec4> kept =
        evaluateCpu(shippedProbe(source, source, {}, production, dfg, executor), c.points, options);
    const std::vector<glm::vec4> extracted =
        evaluateCpu(shippedProbe(residual, source, sun, production, dfg, executor), c.points, options);
    out.keptError = columnErrors(c, reference, &kept);
    out.extractedError = columnErrors(c, reference, &extracted);
    const std::size_t worst =
        std::size_t(std::max_element(out.keptError.begin(), out.keptError.end()) - out.keptError.begin());
    out.warning =
        out.compactLight
            ? compactLightInProbeWarning(out.angularRadiusDegrees, out.keptError[worst], out.roughness[worst],
                                         out.extractedError[worst])
            : sunInProbeWarning(out.keptError[worst], out.roughness[worst], out.extractedError[worst]);
    return out;
}

} // namespace ibl
