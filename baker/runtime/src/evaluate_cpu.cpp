// CPU evaluation: kernels/probe.h's shadePoint over the points.
#include "iblbake/runtime/runtime.h"

#include "point_dispatch.h"

namespace ibl {

std::vector<ShadeResult> shadeCpu(const ProbeSet& set, std::span<const ShadingPoint> points,
                                  const RuntimeOptions& options) {
    const RuntimeParams params = makeRuntimeParams(set, options, points.size());
    const float* distant = set.distantData().data();
    const float* dfg = set.dfg().data.data();
    const LocalProbe* probes = set.localProbes().data();
    const float* localLd = set.localLdData().data();
    std::vector<ShadeResult> out(points.size());
    DispatchGrid::list(points.size()).forEachRange([&](std::size_t first, std::size_t end) {
        for (std::size_t i = first; i < end; ++i)
            out[i] = shadePoint(points[i], params, distant, dfg, probes, localLd);
    });
    return out;
}

std::vector<glm::vec4> evaluateCpu(const ProbeSet& set, std::span<const ShadingPoint> points,
                                   const RuntimeOptions& options) {
    const Dispatcher cpu(nullptr);
    return shadePoints(cpu, set, uploadProbeSet(cpu, set), points, options);
}

} // namespace ibl
