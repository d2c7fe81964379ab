// Cube profiles (iblbake/ktx2/cube_profile.h).
#include "iblbake/ktx2/cube_profile.h"
#include "iblbake/core/error.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace ibl {

CubeProfile parseCubeProfile(const std::string& name) {
    if (name == "standard") return CubeProfile::Standard;
    if (name == "three") return CubeProfile::Three;
    throw Error(valueForMessage(name) + " is not one of standard, three"); // may come from a damaged file
}

const char* cubeProfileName(CubeProfile profile) {
    return profile == CubeProfile::Three ? "three" : "standard";
}

const EngineProfile& engineProfile(const std::string& name) {
    for (const EngineProfile& profile : kEngineProfiles)
        if (name == profile.name) return profile;
    throw Error(valueForMessage(name) + " is not one of standard, three, babylon, filament");
}

float engineLevelRoughness(const EngineProfile& profile, int level, int levelCount, int baseFaceSize) {
    if (profile.levelRule == LevelRule::Baked || level <= 0 || levelCount < 2) return 0.0f;
    if (profile.levelRule == LevelRule::FilamentLod)
        return perceptualRoughnessForLevel(level, levelCount, MipMapping::FilamentLod);
    const double alphaG =
        std::pow(double(baseFaceSize), double(level) / double(levelCount - 1) - 1.0); // 1 at the last level
    return float(std::sqrt(std::max(alphaG - profile.minimumVariance, 0.0)));
}

std::vector<float> engineChainRoughness(const EngineProfile& profile, int levelCount, int baseFaceSize) {
    std::vector<float> roughness;
    for (int m = 0; m < levelCount; ++m)
        roughness.push_back(engineLevelRoughness(profile, m, levelCount, baseFaceSize));
    return roughness;
}

int engineLevelCount(const EngineProfile& profile, int baseFaceSize) {
    int levels = 1;
    while ((baseFaceSize >> levels) >= profile.smallestFace)
        ++levels;
    int full = 1;
    while ((baseFaceSize >> full) > 0)
        ++full;
    return std::min(std::max(levels, profile.minLevels), full);
}

// Direction (x, y, z) -> (-x, y, z) in the OpenGL face table: +X (1, -t, -s) and -X (-1, -t, s) trade
// places with s reversed; on +-Y (s, +-1, ...) and +-Z (s, -t, 1), (-s, -t, -1) s changes sign. So every
// face's columns reverse and +X, -X swap.
void mirrorCubeFacesX(std::span<ImageRGBA> faces) {
    if (faces.size() != 6) throw Error("a cube has 6 faces, not " + std::to_string(faces.size()));
    std::swap(faces[0], faces[1]);
    for (ImageRGBA& face : faces)
        for (int y = 0; y < face.height; ++y) {
            auto row = face.pixels.begin() + std::ptrdiff_t(y) * face.width;
            std::reverse(row, row + face.width);
        }
}

} // namespace ibl
