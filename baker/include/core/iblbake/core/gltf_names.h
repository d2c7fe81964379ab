// The images of a glTF export (iblbake/baker/gltf_ibl.h, gltf_export.h): their names and how many levels
// it holds. Shared by the exporter, which writes them, and the scene planner, which lists them as products
// before anything is baked.
#pragma once

#include <algorithm>
#include <bit>
#include <string>

namespace ibl {

// Level m of the specular chain, face f in +X, -X, +Y, -Y, +Z, -Z order: <stem>_specular_<m>_<px|nx|...>.png.
inline std::string gltfSpecularImageName(const std::string& stem, int level, int face) {
    static constexpr const char* kFaceNames[6] = {"px", "nx", "py", "ny", "pz", "nz"};
    return stem + "_specular_" + std::to_string(level) + "_" + kFaceNames[face] + ".png";
}

// The face size of the roughness-1 level of a chain re-filtered to the extension's linear mapping:
// minFaceSize, but at most half of level 0 (so that roughness 0 and 1 are two levels). 0 for a 1-texel cube.
inline int gltfLowestFaceSize(int baseFaceSize, int minFaceSize) {
    return std::min(minFaceSize, baseFaceSize / 2);
}

// The levels of a re-filtered chain: level 0's face size halving down to the lowest.
inline int gltfRefilteredLevels(int baseFaceSize, int minFaceSize) {
    return std::bit_width(
        unsigned(baseFaceSize / std::max(1, gltfLowestFaceSize(baseFaceSize, minFaceSize))));
}

} // namespace ibl
