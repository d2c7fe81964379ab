// Access to the kernel sources that cmake/EmbedKernels.cmake compiled into the binary.
#pragma once

#include <string_view>
#include <vector>

namespace ibl::ocl {

struct EmbeddedFile {
    std::string_view name;    // file name under kernels/
    std::string_view content; // bytes as in the source tree
};

const std::vector<EmbeddedFile>& embeddedKernelFiles();

} // namespace ibl::ocl
