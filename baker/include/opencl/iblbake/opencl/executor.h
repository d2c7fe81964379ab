// Which backend runs the stages: OpenCL (default) or the CPU backend (TBB), which calls the very same
// kernel functions. When OpenCL has no device, Auto falls back to the CPU with one warning line.
#pragma once

#include "iblbake/core/backend.h"
#include "iblbake/opencl/opencl_context.h"

#include <iosfwd>
#include <memory>
#include <string>

namespace ibl {

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

  private:
    explicit Executor(std::shared_ptr<ocl::Context> cl) : cl_(std::move(cl)) {}
    std::shared_ptr<ocl::Context> cl_;
};

} // namespace ibl
