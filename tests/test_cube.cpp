// Cube and lat-long addressing (kernels/cube.h) against the conventions of docs/conventions.md.
#include <cube.h>

#include <gtest/gtest.h>

namespace {

TEST(Cube, FaceCentresPointAlongTheirAxes) {
    const ibl::vec3 axes[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    for (int f = 0; f < 6; ++f) {
        ibl::vec3 d = ibl::cubeFaceDirection(f, 0.5f, 0.5f);
        EXPECT_EQ(glm::normalize(d), axes[f]) << "face " << f;
    }
    // OpenGL orientation: on +Z, s grows toward +X and t grows toward -Y; on +Y, t grows toward +Z.
    EXPECT_GT(ibl::cubeFaceDirection(4, 1.0f, 0.5f).x, 0.0f);
    EXPECT_LT(ibl::cubeFaceDirection(4, 0.5f, 1.0f).y, 0.0f);
    EXPECT_GT(ibl::cubeFaceDirection(2, 0.5f, 1.0f).z, 0.0f);
    EXPECT_LT(ibl::cubeFaceDirection(0, 1.0f, 0.5f).z, 0.0f); // +X: s grows toward -Z
}

TEST(Cube, DirectionRoundTrip) {
    for (int f = 0; f < 6; ++f)
        for (float s : {0.01f, 0.3f, 0.77f, 0.99f})
            for (float t : {0.02f, 0.5f, 0.93f}) {
                ibl::CubeCoord c = ibl::cubeCoordFromDirection(ibl::cubeFaceDirection(f, s, t));
                EXPECT_EQ(c.face, f);
                EXPECT_NEAR(c.s, s, 1e-6f);
                EXPECT_NEAR(c.t, t, 1e-6f);
            }
}

TEST(Cube, TexelSolidAnglesSumToTheSphere) {
    for (int n : {1, 2, 7, 64}) {
        double sum = 0.0;
        for (int j = 0; j < n; ++j)
            for (int i = 0; i < n; ++i)
                sum += ibl::cubeTexelSolidAngle(i, j, n);
        EXPECT_NEAR(6.0 * sum, 4.0 * 3.14159265358979, 1e-4) << n;
    }
}

TEST(LatLong, FollowsOpenExrLatLongMap) {
    // Image centre looks toward +Z, +X at u = 0.25, the first scanline is the zenith.
    ibl::float2 z = ibl::latlongFromDirection(ibl::vec3(0, 0, 1));
    EXPECT_NEAR(z.x, 0.5f, 1e-6f);
    EXPECT_NEAR(z.y, 0.5f, 1e-6f);
    EXPECT_NEAR(ibl::latlongFromDirection(ibl::vec3(1, 0, 0)).x, 0.25f, 1e-6f);
    EXPECT_NEAR(ibl::latlongFromDirection(ibl::vec3(-1, 0, 0)).x, 0.75f, 1e-6f);
    EXPECT_NEAR(ibl::latlongFromDirection(ibl::vec3(0, 1, 0)).y, 0.0f, 1e-6f);
    for (float u : {0.1f, 0.4f, 0.8f})
        for (float v : {0.2f, 0.5f, 0.9f}) {
            ibl::float2 back = ibl::latlongFromDirection(ibl::directionFromLatlong(u, v));
            EXPECT_NEAR(back.x, u, 1e-5f);
            EXPECT_NEAR(back.y, v, 1e-5f);
        }
}

} // namespace
