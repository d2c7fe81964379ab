#include "iblbake/opencl/executor.h"
#include "iblbake/core/error.h"

#include <algorithm>
#include <cstdlib>
#include <ostream>
#include <utility>

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

Backend jobBackend(Backend requested, bool deviceNamed, const std::vector<ocl::DeviceInfo>& devices) {
    if (requested != Backend::Auto || deviceNamed || devices.empty()) return requested;
    const bool gpu = std::any_of(devices.begin(), devices.end(),
                                 [](const ocl::DeviceInfo& d) { return d.deviceType == "GPU"; });
    const bool allCpus = std::all_of(devices.begin(), devices.end(),
                                     [](const ocl::DeviceInfo& d) { return d.deviceType == "CPU"; });
    return !gpu && allCpus ? Backend::Cpu : Backend::Auto;
}

Backend jobBackend(Backend requested, const std::string& device) {
    if (requested != Backend::Auto) return requested;
    const char* environment = std::getenv("IBLBAKE_CL_DEVICE");
    const bool deviceNamed = !device.empty() || (environment && *environment);
    return deviceNamed ? requested : jobBackend(requested, false, ocl::listDevices());
}

void CpuDispatchTimings::record(const char* kernel, double milliseconds) {
    std::lock_guard lock(mutex_);
    timings_.push_back({kernel, milliseconds});
}

std::vector<ocl::DispatchTiming> CpuDispatchTimings::take() {
    std::lock_guard lock(mutex_);
    return std::exchange(timings_, {});
}

std::vector<ocl::DispatchTiming> Executor::takeTimings() const {
    return cl_ ? cl_->takeTimings() : cpuTimings_->take();
}

std::string Executor::description() const {
    if (!cl_) return "cpu (TBB)";
    return "opencl " + cl_->device().id() + " " + cl_->device().deviceName;
}

} // namespace ibl
