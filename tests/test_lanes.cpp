// The lane code (kernels/lanes.h and the headers that use it) on the host: vector8.h's float8, int8 and uint8
// keep OpenCL C's semantics, and each lane form computes, lane by lane, the bits of the scalar function it
// restates. The CPU backend runs these forms (ld_host_items.cpp), so a difference here is a difference
// between what the CPU bakes and what the scalar functions, and the tests written against them, say.
#include <ld.h>

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

namespace {

using ibl::float8;
using ibl::int8;
using ibl::uint8;

float8 lanesOf(const float (&values)[8]) {
    return ibl::vload8(0, values);
}

float lane(float8 v, int i) {
    return v.v[i];
}

// Bitwise equality that also holds for NaN and tells -0 from +0.
void expectSameBits(float expected, float actual, const char* what, int i) {
    EXPECT_EQ(std::bit_cast<std::uint32_t>(expected), std::bit_cast<std::uint32_t>(actual))
        << what << " lane " << i << ": " << expected << " vs " << actual;
}

TEST(Lanes, BuiltInsKeepOpenClSemantics) {
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const float8 a = lanesOf({-1.5f, 2.7f, -0.0f, 0.0f, nan, 1e30f, -3.0f, 0.25f});
    const float8 b = lanesOf({1.0f, 2.7f, 0.0f, -0.0f, 1.0f, nan, -4.0f, 0.5f});
    const int8 greater = ibl::isgreater(a, b), greaterEqual = ibl::isgreaterequal(a, b);
    const float8 picked = ibl::select(a, b, greater), widest = ibl::fmax(a, b), narrowest = ibl::fmin(a, b);
    const int8 truncated = ibl::convert_int8(a);
    const float8 signs = ibl::copysign(float8(1.0f), a);
    for (int i = 0; i < 8; ++i) {
        const float x = lane(a, i), y = lane(b, i);
        // A comparison is -1 in a true lane, 0 in a false one (and false with a NaN operand).
        EXPECT_EQ(greater.v[i], x > y ? -1 : 0) << i;
        EXPECT_EQ(greaterEqual.v[i], x >= y ? -1 : 0) << i;
        expectSameBits(x > y ? y : x, lane(picked, i), "select", i);
        // fmax/fmin: a NaN operand loses (OpenCL C 6.12.2, as C's).
        expectSameBits(std::fmax(x, y), lane(widest, i), "fmax", i);
        expectSameBits(std::fmin(x, y), lane(narrowest, i), "fmin", i);
        expectSameBits(std::copysign(1.0f, x), lane(signs, i), "copysign", i);
        expectSameBits(std::fabs(x), lane(ibl::fabs(a), i), "fabs", i);
        if (std::isfinite(x) && std::fabs(x) < 1e9f) { // convert_int8 rounds toward zero
            EXPECT_EQ(truncated.v[i], std::int32_t(std::trunc(x))) << i;
        }
    }
    const float8 positive = lanesOf({0.0f, 1e-30f, 2.0f, 3.0f, 1e10f, 0.7f, 123.456f, 1.0f});
    const float8 fractional = lanesOf({-2.5f, -0.5f, 0.5f, 1.0f, 2.999f, -1.0f, 7.25f, -7.25f});
    for (int i = 0; i < 8; ++i) {
        expectSameBits(std::sqrt(lane(positive, i)), lane(ibl::sqrt(positive), i), "sqrt", i);
        expectSameBits(std::floor(lane(fractional, i)), lane(ibl::floor(fractional), i), "floor", i);
        expectSameBits(std::ceil(lane(fractional, i)), lane(ibl::ceil(fractional), i), "ceil", i);
    }
    EXPECT_TRUE(ibl::any(ibl::isless(fractional, -7.0f)));
    EXPECT_FALSE(ibl::any(ibl::isless(positive, 0.0f)));
    EXPECT_EQ(ibl::maxLane(ibl::laneIndices() * -1 + 3), 3);
    // The lanes' sum is pairwise: (l0 + l4) + (l1 + l5) + ..., not left to right.
    const float8 sums = lanesOf({1e8f, 1.0f, 0.0f, 0.0f, -1e8f, 1.0f, 0.0f, 0.0f});
    EXPECT_EQ(ibl::sumLanes(sums), 2.0f);
    const float buffer[5] = {10.0f, 11.0f, 12.0f, 13.0f, 14.0f};
    const float8 gathered = ibl::readLanes(buffer, ibl::as_uint8(ibl::laneIndices() % 5));
    for (int i = 0; i < 8; ++i)
        EXPECT_EQ(lane(gathered, i), buffer[i % 5]);
}

// Random values in [lo, hi] in the 8 lanes.
float8 randomLanes(std::mt19937& rng, float lo, float hi) {
    std::uniform_real_distribution<float> u(lo, hi);
    float8 v;
    for (int i = 0; i < 8; ++i)
        v.v[i] = u(rng);
    return v;
}

TEST(Lanes, LaneFormsAreTheScalarFunctionsLaneByLane) {
    std::mt19937 rng(7);
    for (int round = 0; round < 200; ++round) {
        // atan on every branch of its argument reduction, and a lobe triangle of any orientation.
        const float8 x = randomLanes(rng, -8.0f, 8.0f);
        const float8 atanLanes = ibl::atanPolynomialLanes(x);
        const float8 ax = randomLanes(rng, -1.0f, 1.0f), ay = randomLanes(rng, -1.0f, 1.0f);
        const float8 bx = randomLanes(rng, -1.0f, 1.0f), by = randomLanes(rng, -1.0f, 1.0f);
        const float alpha = std::uniform_real_distribution<float>(1e-4f, 0.5f)(rng);
        const float8 triangle = ibl::lobeTriangleIntegralLanes(ax, ay, bx, by, alpha);
        // Patches both sides of cubePatchSolidAngle's switch from the exact form to the midpoint rule.
        const float step = round % 2 ? 0.05f : 0.01f;
        const float8 u0 = randomLanes(rng, -1.0f, 1.0f - step), v0 = randomLanes(rng, -1.0f, 1.0f - step);
        const float8 solidAngle = ibl::cubePatchSolidAngleLanes(u0, v0, float8(step));
        for (int i = 0; i < 8; ++i) {
            expectSameBits(ibl::atanPolynomial(lane(x, i)), lane(atanLanes, i), "atanPolynomial", i);
            expectSameBits(ibl::lobeTriangleIntegral(ibl::make_float2(lane(ax, i), lane(ay, i)),
                                                     ibl::make_float2(lane(bx, i), lane(by, i)), alpha),
                           lane(triangle, i), "lobeTriangleIntegral", i);
            expectSameBits(ibl::cubePatchSolidAngle(lane(u0, i), lane(v0, i), step), lane(solidAngle, i),
                           "cubePatchSolidAngle", i);
        }
    }
}

TEST(Lanes, CubeSampleLanesReadsWhatCubeSampleLevelReads) {
    // A 4-level pyramid of 8-texel faces, every float distinct.
    const ibl::CubePyramidLayout layout{8u, 4u};
    std::vector<float> pyramid(ibl::cubePyramidFloatCount(layout));
    for (std::size_t i = 0; i < pyramid.size(); ++i)
        pyramid[i] = float(i % 977) * 0.125f + 1.0f;
    std::mt19937 rng(11);
    for (int round = 0; round < 500; ++round) {
        // Directions on every face, edges and corners included, and every level.
        const float8 dx = randomLanes(rng, -1.0f, 1.0f), dy = randomLanes(rng, -1.0f, 1.0f);
        float8 dz = randomLanes(rng, -1.0f, 1.0f);
        if (round % 5 == 0) dz = dx; // on the cube's diagonals and face edges
        const uint8 level = ibl::as_uint8(ibl::laneIndices() % 4);
        float8 r, g, b;
        ibl::cubeSampleLanes(pyramid.data(), layout, level, dx, dy, dz, &r, &g, &b);
        for (int i = 0; i < 8; ++i) {
            const ibl::vec3 expected = ibl::cubeSampleLevel(
                pyramid.data(), layout, level.v[i],
                ibl::cubeCoordFromDirection(ibl::vec3(lane(dx, i), lane(dy, i), lane(dz, i))));
            expectSameBits(expected.x, lane(r, i), "red", i);
            expectSameBits(expected.y, lane(g, i), "green", i);
            expectSameBits(expected.z, lane(b, i), "blue", i);
        }
    }
}

} // namespace
