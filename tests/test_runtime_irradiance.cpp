// Diffuse from the baker's irradiance cube (ProbeSet::setIrradianceCube) instead of the L2 SH: exact on a
// constant environment, closer to the brute-force reference than the SH where a compact light makes L2
// ring, the same on both backends, and loaded from the KTX2 `iblbake diffuse --irradiance-cube` writes.
#include "runtime_test_support.h"

#include <iblbake/core/error.h>
#include <iblbake/ktx2/ktx2.h>
#include <iblbake/runtime/runtime_reference.h>

#include <filesystem>

#include <unistd.h>

namespace {

using namespace ibl;
using namespace rt_test;

// White Lambertian points (f0 = 0, no specular) with normals spread over the sphere.
std::vector<ShadingPoint> diffusePoints() {
    std::vector<ShadingPoint> points;
    const int n = 12;
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < 2 * n; ++i) {
            float theta = (j + 0.5f) / n * IBL_PI, phi = (i + 0.5f) / (2 * n) * 2.0f * IBL_PI;
            glm::vec3 normal(std::sin(theta) * std::cos(phi), std::cos(theta),
                             std::sin(theta) * std::sin(phi));
            points.push_back(makeShadingPoint(glm::vec3(0), normal, normal, glm::vec3(1.0f), 0.0f, 0.5f));
        }
    return points;
}

RuntimeOptions diffuseOnly() {
    RuntimeOptions options;
    options.specular = false;
    options.dielectricF0 = 0.0f;
    return options;
}

TEST(IrradianceCube, ConstantEnvironmentComesBackExactly) {
    const float L = 0.75f;
    CubeMap constant = makeCube(16, [&](glm::vec3) { return glm::vec3(L); });
    std::vector<ShadingPoint> points = diffusePoints();
    // The baked cube (32 px) and a 1 x 1 one (the smallest legal face: its border holds the same value).
    for (int faceSize : {32, 1}) {
        ProbeSet set = distantSet(constant, true);
        if (faceSize == 1) set.setIrradianceCube(makeCube(1, [&](glm::vec3) { return glm::vec3(L); }));
        ASSERT_TRUE(set.hasIrradianceCube());
        std::vector<glm::vec4> out = evaluateCpu(set, points, diffuseOnly());
        for (std::size_t i = 0; i < points.size(); ++i)
            for (int c = 0; c < 3; ++c)
                ASSERT_NEAR(out[i][c], L, 1e-4f * L) << "face size " << faceSize << ", point " << i;
        EXPECT_BACKENDS_AGREE(set, points, diffuseOnly());
    }
}

// Relative mean absolute error of the diffuse against the reference's diffuse (fp64, MIS).
double diffuseError(const ProbeSet& set, const ReferenceLighting& lighting,
                    std::span<const ShadingPoint> points, const RuntimeOptions& options) {
    std::vector<ShadeResult> runtime = shadeCpu(set, points, options);
    std::vector<ReferenceResult> reference = renderReference(lighting, points, options);
    double error = 0.0, sum = 0.0;
    for (std::size_t i = 0; i < points.size(); ++i)
        for (int c = 0; c < 3; ++c) {
            error += std::abs(double(runtime[i].diffuse[c]) - reference[i].diffuse[c]);
            sum += std::abs(reference[i].diffuse[c]);
        }
    return error / sum;
}

TEST(IrradianceCube, CompactLightCloserToReferenceThanSH) {
    // A sky with a bright lobe 10 degrees wide: L2 SH cannot follow its irradiance's sharp fall-off.
    const glm::vec3 toLight = glm::normalize(glm::vec3(0.5f, 0.6f, -0.3f));
    CubeMap sky = makeCube(
        32,
        [&](glm::vec3 d) {
            float lobe = std::pow(std::max(glm::dot(d, toLight), 0.0f), 400.0f);
            return skyLike(d) + glm::vec3(400.0f, 380.0f, 350.0f) * lobe;
        },
        4);
    ProbeSet set = distantSet(sky, true);
    ReferenceLighting lighting = ReferenceLighting::distant(sky);
    std::vector<ShadingPoint> points = diffusePoints();
    RuntimeOptions cube = diffuseOnly(), sh = diffuseOnly();
    sh.irradianceCube = false;
    double cubeError = diffuseError(set, lighting, points, cube),
           shError = diffuseError(set, lighting, points, sh);
    std::printf("diffuse vs reference, compact light: irradiance cube %.2f%%, L2 SH %.2f%%\n",
                100 * cubeError, 100 * shError);
    EXPECT_LT(cubeError, 0.015);
    EXPECT_LT(cubeError, 0.5 * shError);
    EXPECT_BACKENDS_AGREE(set, points, cube);
}

TEST(IrradianceCube, LoadsTheBakersKtx2AndRefusesOtherShapes) {
    namespace fs = std::filesystem;
    fs::path dir = fs::temp_directory_path() / ("iblbake_irradiance_test_" + std::to_string(::getpid()));
    fs::create_directories(dir);
    CubeMap cube = makeCube(8, [](glm::vec3 d) { return glm::abs(d); });
    CubeMapChain chain;
    chain.levels.push_back(cube);
    writeKtx2Cube(dir / "irradiance.ktx2", chain, Ktx2Format::RGBA32F, {});
    CubeMap loaded = loadIrradianceKtx2(dir / "irradiance.ktx2");
    ASSERT_EQ(loaded.faceSize, 8);
    for (int f = 0; f < 6; ++f)
        EXPECT_EQ(loaded.faces[f].pixels, cube.faces[f].pixels) << "face " << f;
    writeKtx2Image(dir / "lut.ktx2", cube.faces[0], Ktx2Format::RGBA32F, {});
    EXPECT_THROW(loadIrradianceKtx2(dir / "lut.ktx2"), Error);
    ProbeSet set = distantSet(cube);
    EXPECT_THROW(set.setIrradianceCube(CubeMap(0)), Error);
    EXPECT_FALSE(set.hasIrradianceCube());
    fs::remove_all(dir);
}

} // namespace
