// The bordered cube pyramid: closed-form layout, borders that make bilinear filtering continuous.
#include <iblbake/core/cube_pyramid.h>
#include <iblbake/core/error.h>

#include <gtest/gtest.h>

namespace {

using namespace ibl;

TEST(CubePyramid, ClosedFormOffsetsMatchTheSumOfLevels) {
    for (uint32_t base : {1u, 2u, 8u, 256u, 4096u}) {
        CubePyramidLayout layout{base, 0};
        uint32_t offset = 0, m = 0;
        for (uint32_t n = base; n >= 1; n /= 2, ++m) {
            EXPECT_EQ(cubeLevelOffset(layout, m), offset) << base << " level " << m;
            EXPECT_EQ(cubeLevelFaceSize(layout, m), n);
            offset += 18u * (n + 2u) * (n + 2u);
        }
    }
}

TEST(CubePyramid, LevelsAverageAndBordersComeFromNeighbours) {
    CubeMap cube(4);
    for (int f = 0; f < 6; ++f)
        for (int y = 0; y < 4; ++y)
            for (int x = 0; x < 4; ++x)
                cube.faces[f].at(x, y) = glm::vec4(float(f * 100 + y * 4 + x), 0, 0, 1);
    CubePyramid p = buildCubePyramid(cube);
    ASSERT_EQ(p.layout.levelCount, 3u);
    ASSERT_EQ(p.data.size(), cubePyramidStorageFloatCount(p.layout));
    // Level 2 (1x1) of face f is the mean of its 16 texels.
    for (int f = 0; f < 6; ++f)
        EXPECT_FLOAT_EQ(p.data[cubeBorderedTexelIndex(p.layout, 2, f, 0, 0)], f * 100 + 7.5f);
    // +Z face (4): its right border (x = 4) is +X's (0) left column, same row (OpenGL orientation).
    for (int y = 0; y < 4; ++y)
        EXPECT_FLOAT_EQ(p.data[cubeBorderedTexelIndex(p.layout, 0, 4, 4, y)], float(0 * 100 + y * 4 + 0));
    // +Z top border (y = -1) is +Y's (2) bottom row.
    for (int x = 0; x < 4; ++x)
        EXPECT_FLOAT_EQ(p.data[cubeBorderedTexelIndex(p.layout, 0, 4, x, -1)], float(2 * 100 + 3 * 4 + x));
}

TEST(CubePyramid, BilinearIsContinuousAcrossFaceEdges) {
    CubeMap cube(8);
    for (int f = 0; f < 6; ++f)
        for (int y = 0; y < 8; ++y)
            for (int x = 0; x < 8; ++x) {
                glm::vec3 d = glm::normalize(cubeFaceDirection(f, (x + 0.5f) / 8, (y + 0.5f) / 8));
                cube.faces[f].at(x, y) = glm::vec4(d.x + 2.0f, d.y + 2.0f, d.z + 2.0f, 1.0f);
            }
    CubePyramid p = buildCubePyramid(cube);
    // Walk across the +Z/+X edge: no jump larger than the smooth signal's own change.
    float previous = -1.0f;
    for (int i = 0; i <= 200; ++i) {
        float angle = glm::radians(40.0f + 10.0f * i / 200.0f); // 45 degrees is the edge
        glm::vec3 d(std::sin(angle), 0.1f, std::cos(angle));
        float v = cubeSampleLevel(p.data.data(), p.layout, 0, cubeCoordFromDirection(d)).x;
        if (previous >= 0.0f) {
            EXPECT_LT(std::abs(v - previous), 0.02f) << "at " << glm::degrees(angle);
        }
        previous = v;
    }
    EXPECT_THROW(buildCubePyramid(CubeMap(6)), Error);
}

} // namespace
