// Options every baking subcommand shares: backend, device and timing.
#pragma once

#include "backend_choice.h"

#include <iblbake/baker/products.h>
#include <iblbake/ktx2/ktx2.h>
#include <iblbake/opencl/executor.h>

#include <CLI/CLI.hpp>

#include <chrono>
#include <future>
#include <string>

namespace ibl::cli {

struct BackendOptions {
    std::string backend = "auto";
    std::string device;
    bool timing = false;

    void addTo(CLI::App& command);
    Executor makeExecutor() const;               // warnings go to stderr
    Executor makeExecutor(Backend chosen) const; // `chosen` instead of --backend's
    // makeExecutor(chosen) on its own thread, so that the OpenCL set-up (PoCL loads LLVM: ~40 ms) overlaps
    // the ingest; get() rethrows its error.
    std::future<Executor> startExecutor(Backend chosen) const;
    // Writes the OpenCL programs the command built from source to the user's kernel cache
    // (ocl::userProgramBinaryDirectory), which makeExecutor gave the executor: called once the command's
    // outputs are complete, so a failed command adds nothing to it.
    static void storeBuiltKernels(const Executor& executor);
    // With --timing: prints the device time of every OpenCL dispatch, and the stage's wall time.
    void printTiming(const Executor& executor, const char* stage, double wallMs) const;
};

// How a command stores its cube product: --format, --clamp-to-format, --profile.
struct CubeStorageOptions {
    std::string format = "rgba16f";
    bool clampToFormat = false;
    std::string profile = "standard";

    void addTo(CLI::App& command, const std::string& product);
};

// --quality: the sample preset (draft, production, reference) of `what`.
void addQualityOption(CLI::App& command, std::string& quality, const std::string& what);

double millisecondsSince(std::chrono::steady_clock::time_point start);

} // namespace ibl::cli
