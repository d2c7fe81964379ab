// Which backend runs the stages: OpenCL (default) or the CPU backend (TBB), which calls the very same
// kernel functions. When OpenCL has no device, Auto falls back to the CPU with one warning line.
#pragma once

#include "iblbake/core/backend.h"
#include "iblbake/opencl/opencl_context.h"

#include <iosfwd>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

namespace ibl {

// The dispatches the CPU backend ran, in order, with their wall times (ocl::Context keeps OpenCL's).
class CpuDispatchTimings {
  public:
    void record(const char* kernel, double milliseconds);
    std::vector<ocl::DispatchTiming> take();

  private:
    std::mutex mutex_;
    std::vector<ocl::DispatchTiming> timings_;
};

class Executor {
  public:
    // Auto: OpenCL if a device is found, else CPU after writing one warning line to `warnings`.
    // OpenCL: throws ibl::Error when no device fits `device`.
    static Executor create(Backend requested, const std::string& device, std::ostream& warnings);
    static Executor cpu() { return Executor(nullptr); }

    bool usesOpenCL() const { return cl_ != nullptr; }
    Backend backend() const { return cl_ ? Backend::OpenCL : Backend::Cpu; }
    ocl::Context& cl() const { return *cl_; }
    std::string description() const;
    // The dispatches run since the last call, in order: each kernel's device time on OpenCL (waiting for
    // those still running), its wall time on the CPU backend.
    std::vector<ocl::DispatchTiming> takeTimings() const;
    // Where the CPU backend's dispatches record their times (nullptr on OpenCL).
    CpuDispatchTimings* cpuTimings() const { return cpuTimings_.get(); }

  private:
    explicit Executor(std::shared_ptr<ocl::Context> cl)
        : cl_(std::move(cl)), cpuTimings_(cl_ ? nullptr : std::make_shared<CpuDispatchTimings>()) {}
    std::shared_ptr<ocl::Context> cl_;
    std::shared_ptr<CpuDispatchTimings> cpuTimings_;
};

// What `auto` runs for a whole job (a command, a scene bake; issue 46): OpenCL when a device is named
// (`deviceNamed`: --device or $IBLBAKE_CL_DEVICE) or a GPU is among `devices`; the CPU backend when every
// device is a CPU (PoCL), since it runs the same lane code compiled ahead of time while OpenCL first pays
// its set-up and compiler (the park scene on PoCL: 18 s of first-use compiles for a 1.5 s bake); Auto
// (OpenCL, else the CPU with a warning) when there is no device. Any other request is kept.
Backend jobBackend(Backend requested, bool deviceNamed, const std::vector<ocl::DeviceInfo>& devices);
// The same for this machine: lists the devices only for Auto without a named device.
Backend jobBackend(Backend requested, const std::string& device);

} // namespace ibl
