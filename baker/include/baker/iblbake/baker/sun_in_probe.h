// A detected sun left in the probe breaks the split sum (a sharp, bright source inside a lobe the LD chain
// pre-filters as if the light were smooth): what it costs at runtime, measured, and the warning that says
// so (`iblbake inspect`, the bake report, `iblbake accuracy`). The same holds for a compact area light the
// sun detector rejects by size (a studio softbox): the check looks for one too, and names the setting that
// extracts it.
#pragma once

#include "iblbake/baker/sun.h"
#include "iblbake/core/cubemap.h"
#include "iblbake/opencl/executor.h"

#include <optional>
#include <string>
#include <vector>

namespace ibl {

// The cube face size the check measures at: a box-filtered copy of the environment (the sun's energy is
// kept; the runtime error it causes is a property of the lobes, not of the texel size).
inline constexpr int kSunInProbeFaceSize = 64;

// The largest bright core the check still calls a compact light, extractable as the disk light with
// `--sun-max-solid-angle` (scene key environment.sunMaxSolidAngle). Measured on studio_small_03 (softbox
// core 6.8e-3 sr) at 256 px, sphere grid 7 against the converged reference (its own error <= 0.36% per
// column): worst runtime column 12.9% with the softbox in the probe, 4.0% with it extracted by a limit of
// 0.01 or 0.02 sr; the shared sun maps extract the same disk with either limit.
inline constexpr double kCompactLightMaxSolidAngle = 0.02;

// takeSunOut (environment.h, IfDetected) with `detection` up to kCompactLightMaxSolidAngle: the compact light
// taken out of `cube` as the disk, or nothing (cube unchanged).
std::optional<DiskLight> takeCompactLightOut(CubeMap& cube, SunDetectSettings detection = {});

// The production probe's runtime error per roughness column (0, 0.1, ..., 1) on the sphere grid (grid x
// grid pixels per camera, sphere_columns.h) against the converged reference, with the light left in and
// extracted, and the warning line. The light: the sun `detection` finds, else a compact light (the same
// detection up to kCompactLightMaxSolidAngle). Nothing (detected false) when neither is found.
struct SunInProbe {
    bool detected = false;
    bool compactLight = false;         // found only with the compact limit: not a sun under `detection`
    double angularRadiusDegrees = 0.0; // of the disk light it becomes
    std::vector<float> roughness;
    std::vector<double> keptError, extractedError;
    std::string warning; // sunInProbeWarning at the worst column
};
SunInProbe measureSunInProbe(const CubeMap& environment, const Executor& executor, int grid = 5,
                             const SunDetectSettings& detection = {});

// "sun detected and left in the probe: runtime error K% at roughness R on the sphere grid (E% with the sun
// extracted); extract it: iblbake --extract-sun, scene key environment.extractSun" (stable wording).
std::string sunInProbeWarning(double keptError, double perceptualRoughness, double extractedError);

// "compact light (disk of D degrees) left in the probe: runtime error K% at roughness R on the sphere grid
// (E% with it extracted as a disk light); extract it: iblbake --extract-sun --sun-max-solid-angle L, scene
// keys environment.extractSun and environment.sunMaxSolidAngle" (stable wording; L =
// kCompactLightMaxSolidAngle).
std::string compactLightInProbeWarning(double angularRadiusDegrees, double keptError,
                                       double perceptualRoughness, double extractedError);

} // namespace ibl
