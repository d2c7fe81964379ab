#include "iblbake/opencl/executor.h"
#include "iblbake/core/error.h"

#include <ostream>

namespace ibl {

Executor Executor::create(Backend requested, const std::string& device, std::ostream& warnings) {
    if (requested == Backend::Cpu) return cpu();
    if (requested == Backend::OpenCL) return Executor(ocl::Context::create(device));
    try {
        return Executor(ocl::Context::create(device));
    } catch (const Error& e) {
        if (!device.empty()) throw; // an explicit device that does not exist is an error, not a fallback
        warnings << "iblbake: warning: " << e.what() << "; running on the CPU backend\n";
        return cpu();
    }
}

std::string Executor::description() const {
    if (!cl_) return "cpu (TBB)";
    return "opencl " + cl_->device().id() + " " + cl_->device().deviceName;
}

} // namespace ibl
