// The lane code (kernels/lanes.h and the headers that use it) on the host: vector8.h's float8, int8 and uint8
// keep OpenCL C's semantics, and each lane form computes, lane by lane, the bits of the scalar function it
// restates. The CPU backend runs these forms (ld_host_items.cpp), so a difference here is a difference
// between what the CPU bakes and what the scalar functions, and the tests written against them, say.
#include "bright_split.h"

#include <ld.h>

#include <gtest/gtest.h>

#include <algorithm>
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
    // vstore8 puts the lanes in order.
    std::uint32_t stored[8];
    ibl::vstore8(ibl::as_uint8(ibl::laneIndices() * 3), 0, stored);
    for (int i = 0; i < 8; ++i)
        EXPECT_EQ(stored[i], std::uint32_t(3 * i));
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

TEST(Lanes, CubeTapPairsLanesAreCubeBilinearTaps) {
    const ibl::CubePyramidLayout layout{8u, 4u};
    std::mt19937 rng(11);
    for (int round = 0; round < 500; ++round) {
        // Directions on every face, edges and corners included, and every level.
        const float8 dx = randomLanes(rng, -1.0f, 1.0f), dy = randomLanes(rng, -1.0f, 1.0f);
        float8 dz = randomLanes(rng, -1.0f, 1.0f);
        if (round % 5 == 0) dz = dx; // on the cube's diagonals and face edges
        const uint8 level = ibl::as_uint8(ibl::laneIndices() % 4);
        uint8 top, bottom;
        float8 fx, fy;
        ibl::cubeTapPairsLanes(layout, level, dx, dy, dz, &top, &bottom, &fx, &fy);
        for (int i = 0; i < 8; ++i) {
            const ibl::CubeBilinearTaps taps = ibl::cubeBilinearTaps(
                layout, level.v[i],
                ibl::cubeCoordFromDirection(ibl::vec3(lane(dx, i), lane(dy, i), lane(dz, i))));
            EXPECT_EQ(top.v[i], 3u * taps.texel00) << i;
            EXPECT_EQ(bottom.v[i], 3u * (taps.texel00 + taps.stride)) << i;
            const float x = lane(fx, i), y = lane(fy, i);
            expectSameBits(taps.w00, (1.0f - x) * (1.0f - y), "w00", i);
            expectSameBits(taps.w10, x * (1.0f - y), "w10", i);
            expectSameBits(taps.w01, (1.0f - x) * y, "w01", i);
            expectSameBits(taps.w11, x * y, "w11", i);
        }
    }
}

// integrateLd against the sum over its table of weight times cubeSampleLevel, in double: the lanes read a
// pair of taps as 8 floats and sum in another order, hence a relative tolerance. The pyramid is exactly its
// storage, so that the reads that reach past the last texel (the 1-texel level's last face) stay inside it
// (and the sanitizer build would see one that did not).
TEST(Lanes, IntegrateLdIsTheWeightedSumOfItsTableSamples) {
    const ibl::CubePyramidLayout layout{8u, 4u};
    std::vector<float> pyramid(ibl::cubePyramidStorageFloatCount(layout));
    for (std::size_t i = 0; i < pyramid.size(); ++i)
        pyramid[i] = float(i % 977) * 0.125f + 1.0f;
    std::mt19937 rng(17);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    for (int round = 0; round < 300; ++round) {
        const std::uint32_t sampleCount = 8u * (1u + rng() % 4);
        std::vector<float> table(IBL_LD_SAMPLE_FLOATS * sampleCount);
        std::vector<ibl::LdSample> samples(sampleCount);
        for (std::uint32_t i = 0; i < sampleCount; ++i) {
            ibl::LdSample& s = samples[i];
            // Any direction of the upper hemisphere, weight 0 sometimes (a sample below the horizon).
            const float z = unit(rng), phi = 6.2831853f * unit(rng), r = std::sqrt(1.0f - z * z);
            s = {r * std::cos(phi), r * std::sin(phi), z, i % 7 == 3 ? 0.0f : z, float(rng() % 4)};
            const float values[] = {s.x, s.y, s.z, s.weight, s.lod};
            for (std::uint32_t c = 0; c < IBL_LD_SAMPLE_FLOATS; ++c)
                table[ibl::ldTableIndex(i, c)] = values[c];
        }
        // Normals anywhere, and at face 5's last corner (its 1-texel level's taps end the pyramid).
        ibl::vec3 normal = round % 10 == 0 ? ibl::vec3(0.4f, -0.4f, -1.0f)
                                           : ibl::vec3(2.0f * unit(rng) - 1.0f, 2.0f * unit(rng) - 1.0f,
                                                       2.0f * unit(rng) - 1.0f);
        normal = ibl::v3normalize(normal);
        const ibl::Frame frame = ibl::frameFromNormal(normal);
        double expected[3] = {0.0, 0.0, 0.0}, weightSum = 0.0;
        for (const ibl::LdSample& s : samples) {
            const ibl::vec3 l = ibl::frameToWorld(frame, ibl::vec3(s.x, s.y, s.z));
            const ibl::vec3 c = ibl::cubeSampleLevel(pyramid.data(), layout, std::uint32_t(s.lod),
                                                     ibl::cubeCoordFromDirection(l));
            expected[0] += double(s.weight) * c.x;
            expected[1] += double(s.weight) * c.y;
            expected[2] += double(s.weight) * c.z;
            weightSum += s.weight;
        }
        const ibl::vec3 actual = ibl::integrateLd(normal, pyramid.data(), layout, table.data(), sampleCount,
                                                  float(1.0 / weightSum));
        const float got[] = {actual.x, actual.y, actual.z};
        for (int c = 0; c < 3; ++c)
            EXPECT_NEAR(got[c], expected[c] / weightSum, 2e-6 * expected[c] / weightSum) << round << " " << c;
    }
}

// brightClusterLd (bright_lanes.h) against brightEntryWeight entry by entry: clusters of 1 to 20 bright
// texels around an output texel, on levels with and without a footprint and with lobes narrow enough for the
// closed form, so that blocks take both the lanes and the one-by-one path. The cluster sits between other
// entries, in the list and in its lanes (brightEntryLanes), so that its blocks start anywhere and read past
// its end. The lanes sum in another order, hence a relative tolerance; a point value in a lane is the scalar
// one's bits.
TEST(Lanes, BrightClusterLanesSumTheEntriesWeights) {
    std::mt19937 rng(13);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    int allPoint = 0, mixed = 0;
    for (int round = 0; round < 400; ++round) {
        const std::uint32_t sourceFaceSize = 4u << (2 * (round % 4)); // 4 .. 256
        const std::uint32_t n = std::max(1u, sourceFaceSize >> (1 + round % 3));
        const float alpha = std::exp(std::log(1e-3f) * unit(rng)); // 1e-3 .. 1
        const float texelSize = 2.0f / float(sourceFaceSize);
        const int face = int(rng() % 6);
        const std::uint32_t x = rng() % n, y = rng() % n;
        // Entries on the output texel's face near it (some within three texels) or anywhere.
        const int count = 1 + int(rng() % 20), before = int(rng() % 10), after = int(rng() % 10);
        std::vector<float> bright;
        for (int i = 0; i < before + count + after; ++i) {
            const bool nearby = rng() % 2 == 0;
            const int entryFace = nearby ? face : int(rng() % 6);
            const float scale = float(sourceFaceSize) / float(n);
            const int spread = int(4.0f * scale) + 1;
            const int bx = nearby ? std::clamp(int(float(x) * scale) + int(rng() % (2 * spread)) - spread, 0,
                                               int(sourceFaceSize) - 1)
                                  : int(rng() % sourceFaceSize);
            const int by = nearby ? std::clamp(int(float(y) * scale) + int(rng() % (2 * spread)) - spread, 0,
                                               int(sourceFaceSize) - 1)
                                  : int(rng() % sourceFaceSize);
            const ibl::vec3 d =
                ibl::cubeTexelDirection(entryFace, std::uint32_t(bx), std::uint32_t(by), sourceFaceSize);
            const float u0 = -1.0f + float(bx) * texelSize, v0 = -1.0f + float(by) * texelSize;
            bright.insert(bright.end(),
                          {d.x, d.y, d.z, ibl::cubePatchSolidAngle(u0, v0, texelSize), 1.0f + unit(rng),
                           2.0f * unit(rng), 1e3f * unit(rng), float(entryFace), float(bx), float(by)});
        }
        ibl::BrightTarget target;
        target.centre = ibl::cubeTexelDirection(face, x, y, n);
        target.frame = ibl::frameFromNormal(target.centre);
        target.face = face;
        target.size = 2.0f / float(n);
        target.u0 = -1.0f + float(x) * target.size;
        target.v0 = -1.0f + float(y) * target.size;
        target.footprint = ibl::ldFootprintApplies(alpha, n);
        target.solidAngle = -1.0f;
        ibl::BrightTarget scalarTarget = target;
        double expected[3] = {0.0, 0.0, 0.0};
        int pointEntries = 0;
        for (int i = before; i < before + count; ++i) {
            const float* e = &bright[std::size_t(i) * IBL_BRIGHT_ENTRY_FLOATS];
            const float weight = ibl::brightEntryWeight(&scalarTarget, e, alpha, texelSize);
            for (int c = 0; c < 3; ++c)
                expected[c] += double(weight) * e[4 + c];
            // brightTexelWeight's point value (no sub-grid, closed form or footprint): the lane form's bits.
            const float cosAngle = ibl::v3dot(target.centre, ibl::v3(e[0], e[1], e[2]));
            const float angle = ibl::chordAngle(cosAngle);
            const bool point =
                (std::ceil(10.0f * texelSize / std::max(angle, alpha)) <= 1.0f || cosAngle < 0.0f) &&
                !ibl::narrowLobeClosedFormApplies(alpha, texelSize, angle) &&
                !(target.footprint && ibl::brightEntryNearFootprint(angle, target.size));
            if (point) {
                ++pointEntries;
                const float8 lanes =
                    ibl::brightPointWeightLanes(target.centre.x, target.centre.y, target.centre.z, e[0], e[1],
                                                e[2], cosAngle, e[3], alpha);
                expectSameBits(weight, lane(lanes, 0), "brightPointWeightLanes", 0);
            }
        }
        allPoint += pointEntries == count;
        mixed += pointEntries > 0 && pointEntries < count;
        const ibl::BrightTexels list{bright, {}};
        const std::vector<float> entryLanes = ibl::brightEntryLanes(list);
        const ibl::vec3 lanes = ibl::brightClusterLd(
            &target, bright.data(), entryLanes.data(), ibl::brightLaneStride(list.count()),
            std::uint32_t(before), std::uint32_t(count), alpha, texelSize);
        const float actual[3] = {lanes.x, lanes.y, lanes.z};
        for (int c = 0; c < 3; ++c)
            EXPECT_NEAR(actual[c], expected[c], 1e-5 * std::abs(expected[c]) + 1e-30)
                << "round " << round << " channel " << c;
    }
    // Both paths taken: clusters of point values only (lanes) and clusters that mix them with near entries.
    EXPECT_GT(allPoint, 20);
    EXPECT_GT(mixed, 20);
}

} // namespace
