// Helpers the stage tests share: backends, synthetic cubes, the error metric, the shared HDRIs.
#pragma once

#include <iblbake/baker/error_metrics.h>
#include <iblbake/baker/ingest.h>
#include <iblbake/core/cubemap.h>
#include <iblbake/opencl/executor.h>

#include <cube.h>

#include <gtest/gtest.h>

#include <cctype>
#include <cmath>
#include <filesystem>
#include <sstream>
#include <string>

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

// The error metric of the stage tests (sum |a - ref| / sum |ref|), from the library.
using ibl::relativeMeanAbsError;

// A file of ../shared/data/hdri (tests skip when it is absent).
// Every RGB value of the cube finite and >= 0 (the hard-case suite's first rule); `what` names the case.
inline void expectFiniteNonNegative(const CubeMap& cube, const char* what) {
    for (const ImageRGBA& face : cube.faces)
        for (const glm::vec4& p : face.pixels)
            for (int c = 0; c < 3; ++c) {
                ASSERT_TRUE(std::isfinite(p[c])) << what;
                ASSERT_GE(p[c], 0.0f) << what;
            }
}

inline std::filesystem::path hdriPath(const char* name) {
    return std::filesystem::path(IBLBAKE_SHARED_DIR) / "data" / "hdri" / name;
}

// The seven HDRIs of ../shared/data/hdri.
inline const char* const kSharedHdris[] = {
    "rooitou_park_1k.hdr",  "potsdamer_platz_1k.hdr", "studio_small_03_1k.hdr",   "venice_sunset_1k.hdr",
    "KernerEnvLatLong.exr", "KernerEnvCube.exr",      "blender_world_sunrise.exr"};

// A test parameterized by one of kSharedHdris; skipped when the file is absent.
class SharedHdriTest : public ::testing::TestWithParam<const char*> {
  protected:
    void SetUp() override {
        if (!std::filesystem::exists(hdriPath(GetParam())))
            GTEST_SKIP() << hdriPath(GetParam()) << " not present";
    }
};

// Test-name suffix for a shared HDRI: its file name with non-alphanumerics as '_'.
inline std::string hdriTestName(const ::testing::TestParamInfo<const char*>& param) {
    std::string name = param.param;
    for (char& c : name)
        if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
    return name;
}

// A shared HDRI ingested to a cube of faceSize texels.
inline CubeMap loadSharedHdri(const char* name, int faceSize) {
    IngestSettings settings;
    settings.sourceFaceSize = faceSize;
    return ingestEnvironment({hdriPath(name)}, settings).cube;
}

} // namespace ibl::test
