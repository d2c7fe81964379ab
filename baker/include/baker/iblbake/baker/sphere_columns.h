// Material spheres shaded by the runtime module from the probe a bake ships, measured column by column
// (one column per roughness) against the converged reference: the measure of `iblbake accuracy`'s runtime
// stage and of the sun-in-probe check (sun_in_probe.h).
#pragma once

#include "iblbake/baker/specular.h"
#include "iblbake/baker/sun.h"
#include "iblbake/core/cubemap.h"
#include "iblbake/opencl/executor.h"

#include <iblbake/runtime/runtime.h>
#include <iblbake/runtime/runtime_reference.h>

#include <optional>
#include <vector>

namespace ibl {

// A dielectric and a metal unit sphere per roughness, each seen by orthographic cameras from +Z and from
// above (grid x grid pixels per camera; pixels whose normal has NoV >= 0.15, where the split sum is meant
// to hold), one column after the other.
struct SphereColumns {
    std::vector<ShadingPoint> points;
    std::vector<std::size_t> start; // of each column, and the end
};
SphereColumns sphereColumns(const std::vector<float>& perceptualRoughness, int grid);

// Per column: sum |shaded - reference| / sum |reference| over its points and RGB; with `shaded` null,
// sum estimate / sum |reference|: the reference's own error in the same measure.
std::vector<double> columnErrors(const SphereColumns& columns, const ConvergedReference& reference,
                                 const std::vector<glm::vec4>* shaded);

// The probe the product ships, from `probeSource` (the residual of an extraction, or the full map when the
// sun stays in), at a specular quality: LD chain with its rough layers (a scene bake ships them when a
// material reads past r_0, as the columns do), DFG, SH, irradiance cube, and the disk light (level 0
// keeps the sun's pixels of `full` when a sun is given). `dfg` is the DFG LUT at its defaults
// (dfgTableFromImage(bakeDfgLut(DfgSettings{}, executor))), baked once by callers that build several probes.
// `chainOut` receives the LD chain.
ProbeSet shippedProbe(const CubeMap& probeSource, const CubeMap& full, const std::optional<SunDisk>& sun,
                      const SpecularSettings& settings, const DfgTable& dfg, const Executor& executor,
                      CubeMapChain* chainOut = nullptr);

} // namespace ibl
