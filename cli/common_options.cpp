#include "common_options.h"

#include <iblbake/bake_state/bake_state.h>
#include <iblbake/ktx2/cube_profile.h>

#include <cstdio>
#include <filesystem>
#include <iostream>

namespace ibl::cli {

void BackendOptions::addTo(CLI::App& command) {
    addBackendAndDevice(command, backend, device);
    command.add_flag("--timing", timing, "print per-dispatch device times and stage wall time");
}

Executor BackendOptions::makeExecutor() const {
    return makeExecutor(parseBackend(backend));
}

Executor BackendOptions::makeExecutor(Backend chosen) const {
    Executor executor = Executor::create(jobBackend(chosen, device), device, std::cerr);
    // A program loaded from its binary skips the compiler and PoCL's own cache look-up, which runs clang's
    // preprocessor over the source (docs/conventions.md "Kernels, backends and kernel binaries").
    if (executor.usesOpenCL())
        if (std::optional<std::filesystem::path> directory = ocl::userProgramBinaryDirectory())
            executor.cl().useProgramBinaries(*directory);
    return executor;
}

void BackendOptions::storeBuiltKernels(const Executor& executor) {
    if (executor.usesOpenCL()) executor.cl().storeProgramBinaries();
}

std::future<Executor> BackendOptions::startExecutor(Backend chosen) const {
    return std::async(std::launch::async, [options = *this, chosen] { return options.makeExecutor(chosen); });
}

void BackendOptions::printTiming(const Executor& executor, const char* stage, double wallMs) const {
    if (!timing) return;
    for (const ocl::DispatchTiming& t : executor.takeTimings())
        std::printf("timing: kernel %-24s %10.3f ms\n", t.kernel.c_str(), t.milliseconds);
    if (executor.usesOpenCL()) {
        const ocl::Context::ProgramBuilds builds = executor.cl().programBuilds();
        std::printf("timing: programs %d built from source, %d loaded from binaries\n", builds.fromSource,
                    builds.fromBinary);
    }
    std::printf("timing: stage  %-24s %10.3f ms (%s)\n", stage, wallMs, executor.description().c_str());
}

void CubeStorageOptions::addTo(CLI::App& command, const std::string& product) {
    std::string formats;
    for (const std::string& name : kKtx2FormatNames)
        formats += (formats.empty() ? "" : ", ") + name;
    command
        .add_option("--format", format,
                    product + " format: " + formats +
                        " (docs/formats.md \"Storage formats\"); an output named .dds is written as DDS")
        ->capture_default_str()
        ->check(CLI::IsMember(kKtx2FormatNames));
    command.add_flag("--clamp-to-format", clampToFormat,
                     "clamp the " + product +
                         " to its format's range (energy lost is reported) instead of "
                         "storing it with a storage scale");
    command
        .add_option("--profile", profile, product + " layout: standard (OpenGL faces), three (three.js r187)")
        ->capture_default_str()
        ->check(CLI::IsMember(kCubeProfileNames));
}

void addQualityOption(CLI::App& command, std::string& quality, const std::string& what) {
    command.add_option("--quality", quality, "sample preset of " + what + ": draft, production, reference")
        ->capture_default_str()
        ->check(CLI::IsMember({"draft", "production", "reference"}));
}

double millisecondsSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

} // namespace ibl::cli
