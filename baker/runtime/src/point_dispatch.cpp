#include "point_dispatch.h"

#include <shade_points.h>

namespace ibl {

ProbeSetInputs uploadProbeSet(const Dispatcher& dispatcher, const ProbeSet& set) {
    return {dispatcher.upload("distant LD pyramid", set.distantData()),
            dispatcher.upload("DFG LUT", set.dfg().data),
            dispatcher.upload("local probes", set.localProbes()),
            dispatcher.upload("local LD pyramids", set.localLdData())};
}

std::vector<glm::vec4> shadePoints(const Dispatcher& dispatcher, const ProbeSet& set,
                                   const ProbeSetInputs& inputs, std::span<const ShadingPoint> points,
                                   const RuntimeOptions& options) {
    DispatchOutput out = dispatcher.output(DispatchGrid::list(points.size()));
    dispatcher.run(kernel("runtime.cl", "shadePoints", shadePointsItem), out,
                   makeRuntimeParams(set, options, points.size()),
                   dispatcher.upload("shading points", points), inputs.distantLd, inputs.dfg, inputs.probes,
                   inputs.localLd);
    return dispatcher.download(out);
}

} // namespace ibl
