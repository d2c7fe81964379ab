// A detected sun left in the probe breaks the split sum (a sharp, bright source inside a lobe the LD chain
// pre-filters as if the light were smooth): what it costs at runtime, measured, and the warning that says
// so (`iblbake inspect`, the bake report, `iblbake accuracy`).
#pragma once

#include "iblbake/core/cubemap.h"
#include "iblbake/opencl/executor.h"

#include <string>
#include <vector>

namespace ibl {

// The cube face size the check measures at: a box-filtered copy of the environment (the sun's energy is
// kept; the runtime error it causes is a property of the lobes, not of the texel size).
inline constexpr int kSunInProbeFaceSize = 64;

// The production probe's runtime error per roughness column (0, 0.1, ..., 1) on the sphere grid (grid x
// grid pixels per camera, sphere_columns.h) against the converged reference, with the sun left in and
// extracted, and the warning line. Nothing (detected false) when no sun is detected.
struct SunInProbe {
    bool detected = false;
    std::vector<float> roughness;
    std::vector<double> keptError, extractedError;
    std::string warning; // sunInProbeWarning at the worst column
};
SunInProbe measureSunInProbe(const CubeMap& environment, const Executor& executor, int grid = 5);

// "sun detected and left in the probe: runtime error K% at roughness R on the sphere grid (E% with the sun
// extracted); extract it: iblbake --extract-sun, scene key environment.extractSun" (stable wording).
std::string sunInProbeWarning(double keptError, double perceptualRoughness, double extractedError);

} // namespace ibl
