// A bake whose LD level 0 kept the extracted sun (`iblbake specular --extract-sun` when the format holds
// it; KTX2 key iblbake.sunInLevel0): the disk light fades out exactly where the lookup reads level 0, so
// the sun is counted once at every roughness.
#include "runtime_test_support.h"

#include <iblbake/ktx2/ktx2.h>

#include <filesystem>

#include <unistd.h>

namespace {

using namespace ibl;
using namespace rt_test;

const glm::vec3 kToSun = glm::normalize(glm::vec3(0.3f, 0.8f, 0.5f));

// A dim sky whose level 0 has the sun's pixels (a 2-degree cap of 1e4) and the matching disk light.
struct SunBake {
    ProbeSet withSunInLevel0, residualOnly;
};

SunBake makeSunBake() {
    auto sky = [](glm::vec3 d) { return glm::vec3(0.2f, 0.3f, 0.5f) * (0.5f + 0.5f * std::max(d.y, 0.0f)); };
    CubeMap residual = makeCube(32, sky);
    CubeMap full = makeCube(32, [&](glm::vec3 d) {
        return sky(d) + (glm::dot(d, kToSun) > std::cos(0.035f) ? glm::vec3(1e4f) : glm::vec3(0.0f));
    });
    CubeMapChain chain = bakeSpecular(residual, SpecularSettings{}, Executor::cpu());
    chain.levels[0] = full;
    LdPyramid ld = ldPyramidFromChain(chain);
    SunDisk sun{kToSun, 0.035f, glm::vec3(1.0f), 1e4f * 3.14159f * 0.035f * 0.035f};
    LdPyramid plain = ld;
    ld.sunInLevel0 = true;
    SunBake bake{ProbeSet(std::move(ld), dfgTableFromImage(dfgLut()), ShCoefficients{}),
                 ProbeSet(std::move(plain), dfgTableFromImage(dfgLut()), ShCoefficients{})};
    bake.withSunInLevel0.setSun(sun);
    bake.residualOnly.setSun(sun);
    return bake;
}

// Metal mirrors-to-rough points whose reflection hits the sun.
std::vector<ShadingPoint> pointsFacingTheSun(float perceptualRoughness) {
    std::vector<ShadingPoint> points;
    for (float tilt : {0.0f, 0.2f, 0.5f}) {
        glm::vec3 view = glm::normalize(glm::vec3(-0.4f, 0.6f + tilt, 0.7f));
        glm::vec3 normal = glm::normalize(view + kToSun); // R = the sun direction
        points.push_back(
            makeShadingPoint(glm::vec3(0), normal, view, glm::vec3(1.0f), 1.0f, perceptualRoughness));
    }
    return points;
}

TEST(SunInLevel0, MirrorReadsTheSunsPixelsAndTheDiskIsFadedOut) {
    SunBake bake = makeSunBake();
    std::vector<ShadingPoint> mirror = pointsFacingTheSun(0.0f);
    RuntimeOptions noSun;
    noSun.sun = false;
    std::vector<ShadeResult> faded = shadeCpu(bake.withSunInLevel0, mirror, {});
    std::vector<ShadeResult> pixelsOnly = shadeCpu(bake.residualOnly, mirror, noSun);
    for (std::size_t i = 0; i < mirror.size(); ++i) {
        EXPECT_GT(faded[i].specular.g, 1e3f) << "the mirror shows the sun's 1e4 pixels";
        EXPECT_NEAR(faded[i].specular.g, pixelsOnly[i].specular.g, 1e-5f * pixelsOnly[i].specular.g)
            << "at level 0 the disk light adds nothing";
    }
    EXPECT_BACKENDS_AGREE(bake.withSunInLevel0, mirror, RuntimeOptions{});
}

TEST(SunInLevel0, AboveTheFirstLevelNothingChanges) {
    SunBake bake = makeSunBake();
    // Frostbite mapping, 6 levels: lod = sqrt(r) * 5 >= 1 from r = 0.04 on; level 0 is not read there.
    for (float r : {0.05f, 0.3f, 1.0f}) {
        std::vector<ShadingPoint> points = pointsFacingTheSun(r);
        std::vector<glm::vec4> a = evaluateCpu(bake.withSunInLevel0, points);
        std::vector<glm::vec4> b = evaluateCpu(bake.residualOnly, points);
        for (std::size_t i = 0; i < points.size(); ++i)
            EXPECT_EQ(a[i], b[i]) << "r = " << r;
    }
}

TEST(SunInLevel0, KeyIsReadFromKtx2) {
    namespace fs = std::filesystem;
    fs::path dir = fs::temp_directory_path() / ("iblbake_sun_level0_" + std::to_string(::getpid()));
    fs::create_directories(dir);
    CubeMapChain chain = bakeSpecular(makeCube(8, skyLike), SpecularSettings{}, Executor::cpu());
    writeKtx2Cube(dir / "with.ktx2", chain, Ktx2Format::RGBA32F, {{"iblbake.sunInLevel0", "true"}});
    writeKtx2Cube(dir / "without.ktx2", chain, Ktx2Format::RGBA32F, {});
    EXPECT_TRUE(loadLdKtx2(dir / "with.ktx2").sunInLevel0);
    EXPECT_FALSE(loadLdKtx2(dir / "without.ktx2").sunInLevel0);
    fs::remove_all(dir);
}

} // namespace
