// OpenCL evaluation: kernels/runtime.cl over the points, through the shared host layer (ocl::Context).
#include "iblbake/error.h"
#include "iblbake/opencl_context.h"
#include "iblbake/runtime.h"

#include <cstddef>

namespace ibl {

// The kernels read these structs from buffers and kernel arguments: 4-byte scalars only, so the C++ and
// OpenCL C layouts agree when the sizes do.
static_assert(sizeof(vec3) == 12, "vec3 must be 3 packed floats as in OpenCL C's struct");
static_assert(sizeof(ShadingPoint) == 60, "ShadingPoint must match kernels/probe.h");
static_assert(sizeof(ProbeVolume) == 64, "ProbeVolume must match kernels/parallax.h");
static_assert(sizeof(LocalProbe) == 160 && offsetof(LocalProbe, fadeDistance) == 156,
              "LocalProbe must match kernels/probe.h");
static_assert(sizeof(RuntimeParams) == 192 && offsetof(RuntimeParams, sh) == 68 &&
                  offsetof(RuntimeParams, irradiance) == 176,
              "RuntimeParams must match kernels/probe.h");

struct OpenCLProbeEvaluator::Buffers {
    cl::Buffer distantLd, dfg, probes, localLd;
    cl::Kernel kernel;
};

OpenCLProbeEvaluator::OpenCLProbeEvaluator(ocl::Context& context, const ProbeSet& set)
    : context_(context), set_(set), buffers_(std::make_unique<Buffers>()) {
    buffers_->distantLd = context_.upload(set.distantData());
    buffers_->dfg = context_.upload(set.dfg().data);
    buffers_->probes = context_.upload(set.localProbes());
    buffers_->localLd = context_.upload(set.localLdData());
    buffers_->kernel = context_.kernel("runtime.cl", "shadePoints");
}

OpenCLProbeEvaluator::~OpenCLProbeEvaluator() = default;

std::vector<glm::vec4> OpenCLProbeEvaluator::evaluate(std::span<const ShadingPoint> points,
                                                      const RuntimeOptions& options) {
    std::vector<glm::vec4> out(points.size());
    if (points.empty()) return out;
    const RuntimeParams params = makeRuntimeParams(set_, options, points.size());
    cl::Buffer pointBuffer = context_.createBuffer(CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR,
                                                   points.size() * sizeof(ShadingPoint), points.data());
    cl::Buffer outBuffer = context_.createBuffer(CL_MEM_WRITE_ONLY, out.size() * sizeof(glm::vec4));
    cl::Kernel& k = buffers_->kernel;
    try {
        k.setArg(0, params);
        k.setArg(1, pointBuffer);
        k.setArg(2, buffers_->distantLd);
        k.setArg(3, buffers_->dfg);
        k.setArg(4, buffers_->probes);
        k.setArg(5, buffers_->localLd);
        k.setArg(6, outBuffer);
    } catch (const cl::Error& e) {
        throw Error(std::string("OpenCL kernel shadePoints: setting arguments failed: ") +
                    ocl::errorName(e.err()));
    }
    const std::size_t group = 64;
    const std::size_t global = (points.size() + group - 1) / group * group;
    context_.run(k, cl::NDRange(global), cl::NDRange(group));
    context_.download(outBuffer, out.size() * sizeof(glm::vec4), out.data());
    lastKernelMs_ = 0.0;
    for (const ocl::DispatchTiming& t : context_.takeTimings())
        if (t.kernel == "shadePoints") lastKernelMs_ = t.milliseconds;
    return out;
}

} // namespace ibl
