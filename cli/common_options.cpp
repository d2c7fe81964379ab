#include "common_options.h"

#include <iblbake/error.h>

#include <cstdio>
#include <iostream>

namespace ibl::cli {

void BackendOptions::addTo(CLI::App& command) {
    addBackendAndDevice(command, backend, device);
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

Ktx2Format parseKtx2Format(const std::string& name) {
    if (name == "rgba16f") return Ktx2Format::RGBA16F;
    if (name == "rgba32f") return Ktx2Format::RGBA32F;
    if (name == "b10g11r11") return Ktx2Format::B10G11R11;
    if (name == "e5b9g9r9") return Ktx2Format::E5B9G9R9;
    throw Error("--format: '" + name + "' is not one of rgba16f, rgba32f, b10g11r11, e5b9g9r9");
}

double millisecondsSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

} // namespace ibl::cli
