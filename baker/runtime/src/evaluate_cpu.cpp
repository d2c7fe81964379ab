// CPU evaluation: kernels/probe.h's shadePoint over the points with TBB.
#include "iblbake/runtime.h"

#include <tbb/parallel_for.h>

namespace ibl {

std::vector<ShadeResult> shadeCpu(const ProbeSet& set, std::span<const ShadingPoint> points,
                                  const RuntimeOptions& options) {
    const RuntimeParams params = makeRuntimeParams(set, options, points.size());
    const float* distant = set.distantData().data();
    const float* dfg = set.dfg().data.data();
    const LocalProbe* probes = set.localProbes().data();
    const float* localLd = set.localLdData().data();
    std::vector<ShadeResult> out(points.size());
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, points.size(), 256),
                      [&](const tbb::blocked_range<std::size_t>& range) {
                          for (std::size_t i = range.begin(); i < range.end(); ++i)
                              out[i] = shadePoint(points[i], params, distant, dfg, probes, localLd);
                      });
    return out;
}

std::vector<glm::vec4> evaluateCpu(const ProbeSet& set, std::span<const ShadingPoint> points,
                                   const RuntimeOptions& options) {
    std::vector<ShadeResult> shaded = shadeCpu(set, points, options);
    std::vector<glm::vec4> out(shaded.size());
    for (std::size_t i = 0; i < shaded.size(); ++i)
        out[i] = glm::vec4(shaded[i].diffuse + shaded[i].specular, shaded[i].localAlpha);
    return out;
}

} // namespace ibl
