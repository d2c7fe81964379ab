// The LD chain of a capture with visibility (Frostbite 2014 4.9.1.2; specular.h bakeSpecularWithVisibility):
// a capture visible everywhere gives the bytes of today's bake, one transparent everywhere is transparent at
// every level, colour x visibility and visibility keep their energy at every level, OpenCL and CPU agree,
// and bad alpha (NaN, negative, above 1) is clamped, counted and gives finite levels.
#include "runtime_test_support.h"

#include <cstring>
#include <limits>
#include <sstream>

namespace {

using namespace ibl;
using namespace rt_test;

// A room seen from its centre, premultiplied: warm walls, a window (visibility 0) toward +X, a half-
// transparent curtain beside it and a lamp 1000 times brighter than the walls (the bake's exact path).
CubeMap capture(int n) {
    CubeMap cube(n);
    for (int f = 0; f < 6; ++f)
        for (int y = 0; y < n; ++y)
            for (int x = 0; x < n; ++x) {
                glm::vec3 d = glm::normalize(glm::vec3(cubeFaceDirection(f, (x + 0.5f) / n, (y + 0.5f) / n)));
                glm::vec3 colour = glm::vec3(0.6f, 0.4f, 0.3f) * (0.7f + 0.3f * d.y) + glm::vec3(0.1f * d.z);
                float visibility = 1.0f;
                if (d.x > 0.8f && std::abs(d.y) < 0.4f) visibility = 0.0f; // window
                if (d.z > 0.85f) visibility = 0.5f + 0.4f * d.x;           // curtain
                if (glm::dot(d, glm::normalize(glm::vec3(-0.3f, 1.0f, 0.2f))) > 0.999f)
                    colour *= 1000.0f; // lamp
                cube.faces[f].at(x, y) = glm::vec4(colour * visibility, visibility);
            }
    return cube;
}

// Solid-angle integral of one channel of a level.
double energy(const CubeMap& level, int channel) {
    double sum = 0.0;
    const int n = level.faceSize;
    for (int f = 0; f < 6; ++f)
        for (int y = 0; y < n; ++y)
            for (int x = 0; x < n; ++x)
                sum += double(level.faces[f].at(x, y)[channel]) * cubeTexelSolidAngle(x, y, n);
    return sum;
}

Executor executorFor(Backend backend) {
    std::ostringstream warnings;
    return Executor::create(backend, "", warnings);
}

TEST(SpecularVisibility, VisibleEverywhereGivesTodaysBytes) {
    CubeMap cube = capture(32);
    for (ImageRGBA& face : cube.faces)
        for (glm::vec4& texel : face.pixels)
            texel.w = 1.0f;
    Executor executor = openclOrCpu();
    VisibilityChain withVisibility = bakeSpecularWithVisibility(cube, SpecularSettings{}, executor);
    CubeMapChain today = bakeSpecular(cube, SpecularSettings{}, executor);
    EXPECT_FALSE(withVisibility.hasVisibility);
    ASSERT_EQ(withVisibility.chain.levels.size(), today.levels.size());
    for (std::size_t m = 0; m < today.levels.size(); ++m)
        for (int f = 0; f < 6; ++f)
            ASSERT_EQ(std::memcmp(withVisibility.chain.levels[m].faces[f].pixels.data(),
                                  today.levels[m].faces[f].pixels.data(),
                                  today.levels[m].faces[f].pixels.size() * sizeof(glm::vec4)),
                      0)
                << "level " << m;
}

TEST(SpecularVisibility, TransparentEverywhereIsTransparentAtEveryLevel) {
    CubeMap cube = capture(32);
    for (ImageRGBA& face : cube.faces)
        for (glm::vec4& texel : face.pixels)
            texel = glm::vec4(0.0f);
    VisibilityChain baked = bakeSpecularWithVisibility(cube, SpecularSettings{}, openclOrCpu());
    EXPECT_TRUE(baked.hasVisibility);
    for (const CubeMap& level : baked.chain.levels)
        for (const ImageRGBA& face : level.faces)
            for (const glm::vec4& texel : face.pixels)
                ASSERT_EQ(texel, glm::vec4(0.0f));
    std::printf("alpha 0 everywhere: %zu levels, every texel RGBA 0\n", baked.chain.levels.size());
}

TEST(SpecularVisibility, EnergyOfColourTimesVisibilityPerLevelAndBackendsAgree) {
    CubeMap cube = capture(32);
    CubeMap visibility(cube.faceSize); // the visibility as a grey cube, for the brute-force reference
    for (int f = 0; f < 6; ++f)
        for (std::size_t i = 0; i < cube.faces[f].pixels.size(); ++i)
            visibility.faces[f].pixels[i] = glm::vec4(glm::vec3(cube.faces[f].pixels[i].w), 1.0f);
    Executor cpu = executorFor(Backend::Cpu);
    VisibilityChain baked = bakeSpecularWithVisibility(cube, SpecularSettings{}, cpu);
    ASSERT_TRUE(baked.hasVisibility);
    EXPECT_EQ(baked.clampedTexels, 0u);
    // The colour is today's filter of colour x visibility, to the bit.
    CubeMapChain premultiplied = bakeSpecular(cube, SpecularSettings{}, cpu);
    for (std::size_t m = 0; m < premultiplied.levels.size(); ++m)
        for (int f = 0; f < 6; ++f)
            for (std::size_t i = 0; i < premultiplied.levels[m].faces[f].pixels.size(); ++i)
                ASSERT_EQ(glm::vec3(baked.chain.levels[m].faces[f].pixels[i]),
                          glm::vec3(premultiplied.levels[m].faces[f].pixels[i]));
    // Energy of each level against the brute-force LD of the same level (every source texel, fp64): the
    // filter's own loss, apart from what sampling a level at its texel centres does to a window's edge.
    const int levelCount = int(baked.chain.levels.size());
    double worst = 0.0;
    for (int m = 1; m < levelCount; ++m) {
        const int n = cube.faceSize >> m;
        const float r = perceptualRoughnessForLevel(m, levelCount, MipMapping::Frostbite);
        const CubeMap colourRef = referenceSpecularLevel(cube, n, r),
                      visibilityRef = referenceSpecularLevel(visibility, n, r);
        std::printf("level %d (%d px, r %.3f):", m, n, r);
        for (int c = 0; c < 4; ++c) {
            double reference = c < 3 ? energy(colourRef, c) : energy(visibilityRef, 0);
            double e = energy(baked.chain.levels[std::size_t(m)], c) / reference - 1.0;
            worst = std::max(worst, std::abs(e));
            std::printf(" %+.3f%%", 100.0 * e);
            EXPECT_LT(std::abs(e), 0.005) << "level " << m << " channel " << c;
        }
        std::printf("  (R G B x visibility, visibility)\n");
    }
    std::printf("energy per level against the brute force: worst %.3f%%\n", 100.0 * worst);

    Executor opencl = executorFor(Backend::Auto);
    if (!opencl.usesOpenCL()) GTEST_SKIP() << "no OpenCL device";
    VisibilityChain clBaked = bakeSpecularWithVisibility(cube, SpecularSettings{}, opencl);
    double difference = 0.0;
    for (std::size_t m = 0; m < baked.chain.levels.size(); ++m)
        for (int f = 0; f < 6; ++f)
            for (std::size_t i = 0; i < baked.chain.levels[m].faces[f].pixels.size(); ++i)
                for (int c = 0; c < 4; ++c) {
                    float a = clBaked.chain.levels[m].faces[f].pixels[i][c],
                          b = baked.chain.levels[m].faces[f].pixels[i][c];
                    difference = std::max(difference, double(std::abs(a - b)) / std::max(std::abs(b), 1e-3f));
                }
    std::printf("OpenCL vs CPU: max relative difference %.3g (RGBA, every level)\n", difference);
    EXPECT_LT(difference, 1e-3);
}

TEST(SpecularVisibilityHardCases, NaNNegativeAndAboveOneAreClampedAndCounted) {
    CubeMap cube = capture(16);
    const float values[4] = {std::numeric_limits<float>::quiet_NaN(), -0.25f,
                             std::numeric_limits<float>::infinity(), 3.0f};
    std::size_t planted = 0;
    for (ImageRGBA& face : cube.faces)
        for (std::size_t i = 0; i < face.pixels.size(); i += 5)
            face.pixels[i].w = values[planted++ % 4];
    VisibilityChain baked = bakeSpecularWithVisibility(cube, SpecularSettings{}, openclOrCpu());
    EXPECT_EQ(baked.clampedTexels, planted);
    for (const CubeMap& level : baked.chain.levels)
        for (const ImageRGBA& face : level.faces)
            for (const glm::vec4& texel : face.pixels) {
                ASSERT_TRUE(std::isfinite(texel.x + texel.y + texel.z));
                ASSERT_TRUE(texel.w >= 0.0f && texel.w <= 1.0f) << texel.w;
            }
    // Level 0 is the sanitized source: NaN and negative alpha transparent, above 1 visible.
    const ImageRGBA& face0 = baked.chain.levels[0].faces[0];
    EXPECT_EQ(face0.pixels[0], glm::vec4(0.0f)); // NaN
    EXPECT_EQ(face0.pixels[5], glm::vec4(0.0f)); // -0.25
    EXPECT_EQ(face0.pixels[10].w, 1.0f);         // +inf
    EXPECT_EQ(glm::vec3(face0.pixels[10]), glm::vec3(cube.faces[0].pixels[10]));
    std::printf("%zu bad alpha texels clamped and counted; every level finite, alpha in [0, 1]\n", planted);
}

} // namespace
