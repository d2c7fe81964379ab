// OpenCL evaluation: kernels/runtime.cl over the points, through the dispatch helper (point_dispatch.h).
#include "iblbake/opencl/opencl_context.h"
#include "iblbake/runtime/runtime.h"

#include "point_dispatch.h"

#include <cstddef>

namespace ibl {

// The kernels read these structs from buffers and kernel arguments: 4-byte scalars only, so the C++ and
// OpenCL C layouts agree when the sizes do.
static_assert(sizeof(vec3) == 12, "vec3 must be 3 packed floats as in OpenCL C's struct");
static_assert(sizeof(ShadingPoint) == 60, "ShadingPoint must match kernels/probe.h");
static_assert(sizeof(ProbeVolume) == 64, "ProbeVolume must match kernels/parallax.h");
static_assert(sizeof(LocalProbe) == 168 && offsetof(LocalProbe, fadeDistance) == 156 &&
                  offsetof(LocalProbe, visibilityOffset) == 164,
              "LocalProbe must match kernels/probe.h");
static_assert(sizeof(RuntimeParams) == 204 && offsetof(RuntimeParams, sh) == 68 &&
                  offsetof(RuntimeParams, irradiance) == 176 &&
                  offsetof(RuntimeParams, distantRoughLayers) == 192,
              "RuntimeParams must match kernels/probe.h");

struct OpenCLProbeEvaluator::Buffers {
    Dispatcher dispatcher;
    ProbeSetInputs inputs;
};

OpenCLProbeEvaluator::OpenCLProbeEvaluator(ocl::Context& context, const ProbeSet& set)
    : context_(context), set_(set) {
    Dispatcher dispatcher(&context_);
    buffers_ = std::make_unique<Buffers>(Buffers{dispatcher, uploadProbeSet(dispatcher, set)});
}

OpenCLProbeEvaluator::~OpenCLProbeEvaluator() = default;

std::vector<glm::vec4> OpenCLProbeEvaluator::evaluate(std::span<const ShadingPoint> points,
                                                      const RuntimeOptions& options) {
    std::vector<glm::vec4> out = shadePoints(buffers_->dispatcher, set_, buffers_->inputs, points, options);
    lastKernelMs_ = 0.0;
    for (const ocl::DispatchTiming& t : context_.takeTimings())
        if (t.kernel == "shadePoints") lastKernelMs_ = t.milliseconds;
    return out;
}

} // namespace ibl
