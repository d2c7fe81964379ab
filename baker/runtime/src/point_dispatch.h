// The shading of points on either backend (iblbake/opencl/dispatch.h): kernels/runtime.cl on OpenCL, its
// work-item function kernels/shade_points.h on the CPU.
#pragma once

#include "iblbake/opencl/dispatch.h"
#include "iblbake/runtime/runtime.h"

#include <span>
#include <vector>

namespace ibl {

// A probe set's arrays as kernel inputs: uploaded once on OpenCL, the set's own on the CPU.
struct ProbeSetInputs {
    DeviceArray<float> distantLd, dfg;
    DeviceArray<LocalProbe> probes;
    DeviceArray<float> localLd;
};
ProbeSetInputs uploadProbeSet(const Dispatcher& dispatcher, const ProbeSet& set);

// RGB radiance and the local probes' composed alpha per point.
std::vector<glm::vec4> shadePoints(const Dispatcher& dispatcher, const ProbeSet& set,
                                   const ProbeSetInputs& inputs, std::span<const ShadingPoint> points,
                                   const RuntimeOptions& options);

} // namespace ibl
