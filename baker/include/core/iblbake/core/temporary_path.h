// The one naming rule for files and directories written under a temporary name and then renamed into
// place (AtomicFile, OutputSet, the program-binary cache, the accuracy reports).
#pragma once

#include <filesystem>

namespace ibl {

// A hidden name beside `target` (same directory, so the rename is atomic and needs no space) that no other
// writer uses: process id, a per-process counter and 24 random bits, so threads, processes and machines
// sharing the directory (a farm's cache) never collide. It keeps the target's extension, since writers
// pick the format by it: "dir/.name.tmp-<pid>-<n>-<random>.ext" for "dir/name.ext".
std::filesystem::path temporaryPathBeside(const std::filesystem::path& target);

} // namespace ibl
