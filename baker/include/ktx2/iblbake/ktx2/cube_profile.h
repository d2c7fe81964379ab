// Target profiles of the cube KTX2 products (`--profile` of `iblbake specular` / `diffuse`, the scene's
// outputs.profile), recorded in every cube as the key iblbake.profile and in the scene manifest.
// - standard: docs/conventions.md's cube (OpenGL faces and face orientation in a right-handed, +Y-up frame).
// - three: what three.js r187's cube-texture path shows right. three samples a CubeTexture that is not
//   a render target at (-x, y, z) of the world direction (flipEnvMap = -1 in scene.background's box,
//   PMREMGenerator.fromCubemap and MeshStandardMaterial.envMap), so the stored cube is ours mirrored in
//   x: +X and -X faces swapped, the columns of every face reversed.
// writeKtx2Cube stores the layout its iblbake.profile key declares; readKtx2 returns every cube in the
// standard layout, so iblbake's own readers (runtime, `iblbake gltf`) never see the difference.
#pragma once

#include "iblbake/core/image.h"

#include <span>
#include <string>
#include <vector>

namespace ibl {

enum class CubeProfile { Standard, Three };
inline const std::vector<std::string> kCubeProfileNames = {"standard", "three"};
inline constexpr const char* kCubeProfileKey = "iblbake.profile";

// Throws ibl::Error "'<name>' is not one of standard, three" for any other name.
CubeProfile parseCubeProfile(const std::string& name);
const char* cubeProfileName(CubeProfile profile);

// Mirrors six faces (+X, -X, +Y, -Y, +Z, -Z) in x, in place: the three profile's layout from the
// standard one and back (the mirror is its own inverse).
void mirrorCubeFacesX(std::span<ImageRGBA> faces);

} // namespace ibl
