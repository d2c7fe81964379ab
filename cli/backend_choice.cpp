#include "backend_choice.h"

namespace ibl::cli {

void addBackendAndDevice(CLI::App& command, std::string& backend, std::string& device) {
    command
        .add_option("--backend", backend,
                    "auto (OpenCL on a GPU or a named device, else the CPU lanes), opencl or cpu")
        ->check(CLI::IsMember({"auto", "opencl", "cpu"}));
    command.add_option(
        "--device", device,
        "OpenCL device: P:D index or part of its name (default: $IBLBAKE_CL_DEVICE, else first GPU, "
        "else first device)");
}

} // namespace ibl::cli
