// Where a scene or batch file may send outputs (docs/scenes.md "Untrusted scene files", docs/batch.md
// "Batch"): a relative output path resolves against the file's directory and may not leave it, so a file
// written by someone else cannot make a bake write elsewhere ("../../etc"). An absolute path, or a path given
// on the command line, is the user's explicit choice and is not confined.
#pragma once

#include <filesystem>
#include <string_view>

namespace ibl {

// Whether a relative path, once "." and ".." are resolved without looking at the disk, leaves the directory
// it is relative to ("../x", "a/../../x"). An absolute path never does.
inline bool leavesItsDirectory(std::string_view path) {
    const std::filesystem::path p(path);
    if (p.is_absolute()) return false;
    const std::filesystem::path normal = p.lexically_normal();
    return !normal.empty() && *normal.begin() == "..";
}

} // namespace ibl
