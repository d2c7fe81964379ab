// --backend and --device: declared once for every command that runs kernels (and for the front end, which
// parses `iblbake bake` without starting a backend).
#pragma once

#include <CLI/CLI.hpp>

#include <string>

namespace ibl::cli {

// --backend (auto, opencl, cpu) and --device, bound to the caller's strings.
void addBackendAndDevice(CLI::App& command, std::string& backend, std::string& device);

} // namespace ibl::cli
