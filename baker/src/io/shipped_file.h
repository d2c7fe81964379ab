// Files shipped with the programs (the OCIO config, the OpenImageIO module): an installed program's, found
// from the program's own path so that any install prefix works (cmake --install --prefix, the .deb), else
// the build tree's that a build-tree program was built from.
#pragma once

#include <string>

namespace ibl {

// `relativeToProgram` resolved against the running program's directory when that file exists, else
// `buildTreePath`.
std::string shippedFile(const std::string& relativeToProgram, const std::string& buildTreePath);

} // namespace ibl
