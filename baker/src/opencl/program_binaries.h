// Program binaries kept on disk (docs/conventions.md "Kernels, backends and kernel binaries"), so that a farm
// node with a warm cache directory pays the OpenCL compiler once per cache, not once per machine. A binary is
// found under a key that holds everything its validity depends on: platform, device, driver version, build
// options and the whole assembled source. A file is used only when its header names that key and its payload
// matches the hash it carries; anything else (stale, foreign, truncated, corrupt) is ignored and rebuilt.
#pragma once

#define CL_HPP_TARGET_OPENCL_VERSION 120
#define CL_HPP_MINIMUM_OPENCL_VERSION 120
#define CL_HPP_ENABLE_EXCEPTIONS
#include <CL/opencl.hpp>

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace ibl::ocl {

using ProgramBinary = std::vector<unsigned char>;

// 32 hex digits (XXH3-128) of the device's identity, `options` and `source`.
std::string programBinaryKey(const cl::Device& device, const std::string& options, const std::string& source);

// The payload of <directory>/<key>.clbin when it is whole and is for `key`; nullopt otherwise.
std::optional<ProgramBinary> readProgramBinary(const std::filesystem::path& directory,
                                               const std::string& key);

// Writes <directory>/<key>.clbin through a temporary file and a rename (created with the directory when
// missing). Returns false, writing nothing, when it cannot: a cache that cannot be written costs only time.
bool writeProgramBinary(const std::filesystem::path& directory, const std::string& key,
                        const ProgramBinary& binary);

} // namespace ibl::ocl
