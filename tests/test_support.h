// Helpers the stage tests share: backends, synthetic cubes, the error metric, the shared HDRIs.
#pragma once

#include <iblbake/cubemap.h>
#include <iblbake/executor.h>

#include <cube.h>

#include <cmath>
#include <filesystem>
#include <sstream>

namespace ibl::test {

// OpenCL when a device exists, else the CPU backend (then the comparisons are CPU against CPU).
inline Executor openclOrCpu() {
    std::ostringstream warnings;
    return Executor::create(Backend::Auto, "", warnings);
}

// Unit direction through the centre of texel (x, y) of face f of an n-texel cube, in fp64.
inline glm::dvec3 texelCentre(int f, int x, int y, int n) {
    return glm::normalize(glm::dvec3(cubeFaceDirection(f, (x + 0.5f) / n, (y + 0.5f) / n)));
}

// A cube whose texels hold radiance(direction of the texel centre); alpha 1.
template <class F>
CubeMap makeCube(int n, F radiance) {
    CubeMap c(n);
    for (int f = 0; f < 6; ++f)
        for (int y = 0; y < n; ++y)
            for (int x = 0; x < n; ++x)
                c.faces[f].at(x, y) = glm::vec4(glm::vec3(radiance(texelCentre(f, x, y, n))), 1.0f);
    return c;
}

// Relative mean absolute error over every texel and colour channel: sum |a - ref| / sum |ref|.
inline double relativeMeanAbsError(const CubeMap& a, const CubeMap& ref) {
    double err = 0.0, sum = 0.0;
    for (int f = 0; f < 6; ++f)
        for (std::size_t i = 0; i < a.faces[f].pixels.size(); ++i)
            for (int c = 0; c < 3; ++c) {
                err += std::abs(double(a.faces[f].pixels[i][c]) - ref.faces[f].pixels[i][c]);
                sum += std::abs(double(ref.faces[f].pixels[i][c]));
            }
    return err / sum;
}

// A file of ../shared/data/hdri (tests skip when it is absent).
inline std::filesystem::path hdriPath(const char* name) {
    return std::filesystem::path(IBLBAKE_SHARED_DIR) / "data" / "hdri" / name;
}

} // namespace ibl::test
