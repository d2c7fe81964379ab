#include "common_options.h"

#include <cstdio>
#include <iostream>

namespace ibl::cli {

void BackendOptions::addTo(CLI::App& command) {
    command.add_option("--backend", backend, "auto (OpenCL, else CPU with a warning), opencl or cpu")
        ->check(CLI::IsMember({"auto", "opencl", "cpu"}));
    command.add_option(
        "--device", device,
        "OpenCL device: P:D index or part of its name (default: $IBLBAKE_CL_DEVICE, else first GPU, "
        "else first device)");
    command.add_flag("--timing", timing, "print per-dispatch device times and stage wall time");
}

Executor BackendOptions::makeExecutor() const {
    return Executor::create(parseBackend(backend), device, std::cerr);
}

void BackendOptions::printTiming(const Executor& executor, const char* stage, double wallMs) const {
    if (!timing) return;
    if (executor.usesOpenCL())
        for (const ocl::DispatchTiming& t : executor.cl().takeTimings())
            std::printf("timing: kernel %-24s %10.3f ms\n", t.kernel.c_str(), t.milliseconds);
    std::printf("timing: stage  %-24s %10.3f ms (%s)\n", stage, wallMs, executor.description().c_str());
}

} // namespace ibl::cli
