// The code behind a stage's bytes (docs/scenes.md "Cache"): which sources decide each stage kind is listed in
// cmake/StageCode.cmake, and the build hashes them (cmake/StageCodeIdentity.cmake) into this table, which
// every stage-cache key holds, so a build with a changed kernel or stage never reuses an old entry.
#pragma once

#include <map>
#include <string>

namespace ibl {

// Stage kind ("dfg-lut", "specular-ld", ...) -> SHA-256 (hex) of the C++ and kernel sources of that kind.
using StageCodeIdentity = std::map<std::string, std::string>;

// This build's table.
const StageCodeIdentity& builtInStageCodeIdentity();

// The first 12 hex digits of a SHA-256 over the whole table: this build's stage code in one short word
// (`iblbake --version`).
const char* builtInCodeDigest();

} // namespace ibl
