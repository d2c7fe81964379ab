// KTX2 writer and reader: round trips of every format with stated tolerances, the exact bytes the KTX 2.0
// specification requires (header, DFD, key/value data, level index and padding), rounding and sanitizing,
// failure behaviour of the writer, and a reader that rejects damaged files with ibl::Error.
#include "iblbake/core/error.h"
#include "iblbake/ktx2/cube_profile.h"
#include "iblbake/ktx2/ktx2.h"

#include <cube.h>
#include <small_float.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <csignal>
#include <cstring>
#include <fstream>
#include <random>
#include <sys/resource.h>
#include <unistd.h>

namespace {

namespace fs = std::filesystem;

// The small float encoders (baker/src/io/small_float.h) at every code of the 5-bit-exponent formats: each
// code's value encodes back to itself, the value halfway to the next code rounds to the even one of the two,
// and the floats just either side of it to the nearer one. Negative halves carry the sign bit.
TEST(SmallFloat, EveryCodeRoundTripsAndTiesGoToEven) {
    for (int mantissaBits : {10, 6, 5}) {
        const std::uint32_t largest =
            (30u << mantissaBits) | ((1u << mantissaBits) - 1u); // exponent 30, all ones
        for (std::uint32_t code = 0; code <= largest; ++code) {
            const float value = ibl::smallfloat::decodeMagnitude(code, mantissaBits);
            ASSERT_EQ(ibl::smallfloat::encodeMagnitude(value, mantissaBits), code)
                << mantissaBits << " " << code;
            if (code == largest) break;
            const double next = ibl::smallfloat::decodeMagnitude(code + 1, mantissaBits);
            const float halfway = float(0.5 * (double(value) + next)); // exact: one bit more than the code
            ASSERT_EQ(double(halfway), 0.5 * (double(value) + next));
            ASSERT_EQ(ibl::smallfloat::encodeMagnitude(halfway, mantissaBits),
                      code % 2 == 0 ? code : code + 1)
                << mantissaBits << " " << code;
            ASSERT_EQ(ibl::smallfloat::encodeMagnitude(std::nextafter(halfway, 0.0f), mantissaBits), code);
            ASSERT_EQ(ibl::smallfloat::encodeMagnitude(std::nextafter(halfway, INFINITY), mantissaBits),
                      code + 1);
        }
    }
    EXPECT_EQ(ibl::smallfloat::floatToHalf(-1.0f), 0xBC00u);
    EXPECT_EQ(ibl::smallfloat::floatToHalf(-0.0f), 0x8000u);
    EXPECT_EQ(ibl::smallfloat::floatToHalf(1e-10f), 0u); // far under the smallest subnormal half
}
using ibl::Ktx2Format;

// A fresh directory per test, removed afterwards.
class TempDir {
  public:
    TempDir() {
        const auto* test = ::testing::UnitTest::GetInstance()->current_test_info();
        std::string name = std::string("iblbake_ktx2_") + test->test_suite_name() + "_" + test->name() + "_" +
                           std::to_string(::getpid());
        std::replace(name.begin(), name.end(), '/', '_');
        path_ = fs::temp_directory_path() / name;
        fs::remove_all(path_);
        fs::create_directories(path_);
    }
    ~TempDir() {
        std::error_code ec;
        fs::remove_all(path_, ec);
    }
    fs::path operator/(const std::string& file) const { return path_ / file; }
    const fs::path& path() const { return path_; }

  private:
    fs::path path_;
};

std::vector<std::uint8_t> readBytes(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void writeBytes(const fs::path& path, const std::vector<std::uint8_t>& bytes) {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
}

std::uint32_t u32At(const std::vector<std::uint8_t>& b, std::size_t at) {
    std::uint32_t v = 0;
    for (int i = 0; i < 4; ++i)
        v |= std::uint32_t(b.at(at + i)) << (8 * i);
    return v;
}

std::uint64_t u64At(const std::vector<std::uint8_t>& b, std::size_t at) {
    return u32At(b, at) | (std::uint64_t(u32At(b, at + 4)) << 32);
}

std::vector<std::string> filesIn(const fs::path& dir) {
    std::vector<std::string> names;
    for (const auto& entry : fs::directory_iterator(dir))
        names.push_back(entry.path().filename().string());
    std::sort(names.begin(), names.end());
    return names;
}

// Expects readKtx2 to throw ibl::Error whose message starts with the file name.
::testing::AssertionResult rejects(const fs::path& path) {
    try {
        ibl::readKtx2(path);
    } catch (const ibl::Error& e) {
        if (std::string(e.what()).rfind(path.string() + ": ", 0) == 0) return ::testing::AssertionSuccess();
        return ::testing::AssertionFailure() << "message does not start with the file name: " << e.what();
    }
    return ::testing::AssertionFailure() << "accepted";
}

struct FormatCase {
    Ktx2Format format;
    std::uint32_t vkFormat;
    std::uint32_t typeSize;
    std::uint32_t texelBytes;
    bool hasAlpha;
    bool isSigned;
    const char* name;
};

const FormatCase kCases[] = {
    {Ktx2Format::RGBA16F, 97, 2, 8, true, true, "RGBA16F"},
    {Ktx2Format::RGBA32F, 109, 4, 16, true, true, "RGBA32F"},
    {Ktx2Format::B10G11R11, 122, 4, 4, false, false, "B10G11R11"},
    {Ktx2Format::E5B9G9R9, 123, 4, 4, false, false, "E5B9G9R9"},
};

// Values log-uniform in [2^-8, 2^12] (every format's normal range), negative half of the time for the
// signed formats; alpha in [2^-8, 1]. Every texel of every face and level differs, so any mix-up of
// faces, levels or rows shows up as a large error.
ibl::CubeMapChain randomChain(int base, int levelCount, bool signedValues, std::uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> logValue(-8.0f, 12.0f), logAlpha(-8.0f, 0.0f);
    std::bernoulli_distribution negative(signedValues ? 0.5 : 0.0);
    ibl::CubeMapChain chain;
    for (int m = 0; m < levelCount; ++m) {
        ibl::CubeMap level(std::max(1, base >> m));
        for (ibl::ImageRGBA& face : level.faces)
            for (glm::vec4& p : face.pixels) {
                for (int c = 0; c < 3; ++c)
                    p[c] = std::exp2(logValue(rng)) * (negative(rng) ? -1.0f : 1.0f);
                p.a = std::exp2(logAlpha(rng));
            }
        chain.levels.push_back(std::move(level));
    }
    return chain;
}

// Largest error a stored channel may have (round to nearest in each format):
//   RGBA32F   exact.
//   RGBA16F   11 significant bits, ties to even: at most half an ulp, 2^-11 |v| for normal values.
//   B10G11R11 R and G keep 6 mantissa bits (2^-7 |v|), B keeps 5 (2^-6 |v|).
//   E5B9G9R9  the shared exponent puts the largest channel's 9-bit mantissa in [256, 511] after rounding,
//             so the step is at most max(r,g,b)/255.5 and every channel is within half a step:
//             max(r,g,b)/511.
float tolerance(Ktx2Format format, int channel, const glm::vec4& v) {
    switch (format) {
    case Ktx2Format::RGBA32F:
        return 0.0f;
    case Ktx2Format::RGBA16F:
        return std::ldexp(std::abs(v[channel]), -11);
    case Ktx2Format::B10G11R11:
        return std::ldexp(std::abs(v[channel]), channel == 2 ? -6 : -7);
    case Ktx2Format::E5B9G9R9:
        return std::max({v.r, v.g, v.b}) / 511.0f;
    default: // the BC6H formats: blocks, not texels (test_bc6h.cpp)
        break;
    }
    return 0.0f;
}

class Ktx2Formats : public ::testing::TestWithParam<FormatCase> {};

INSTANTIATE_TEST_SUITE_P(AllFormats, Ktx2Formats, ::testing::ValuesIn(kCases),
                         [](const auto& test) { return std::string(test.param.name); });

TEST_P(Ktx2Formats, CubeChainRoundTripsWithinFormatTolerance) {
    const FormatCase& fc = GetParam();
    TempDir dir;
    const ibl::CubeMapChain chain = randomChain(8, 4, fc.isSigned, 1234);
    const ibl::Ktx2WriteStats stats = ibl::writeKtx2Cube(dir / "cube.ktx2", chain, fc.format, {});
    EXPECT_EQ(stats.clampedTexels, 0u);
    EXPECT_EQ(stats.repairedNonFinite, 0u);

    const ibl::Ktx2Image image = ibl::readKtx2(dir / "cube.ktx2");
    EXPECT_EQ(image.vkFormat, fc.vkFormat);
    EXPECT_EQ(image.pixelWidth, 8u);
    EXPECT_EQ(image.pixelHeight, 8u);
    EXPECT_EQ(image.faceCount, 6u);
    EXPECT_EQ(image.levelCount, 4u);
    ASSERT_EQ(image.levels.size(), 4u);
    int failures = 0;
    for (int m = 0; m < 4; ++m) {
        ASSERT_EQ(image.levels[m].size(), 6u);
        for (int f = 0; f < 6; ++f) {
            const ibl::ImageRGBA& in = chain.levels[m].faces[f];
            const ibl::ImageRGBA& out = image.levels[m][f];
            ASSERT_EQ(out.width, 8 >> m);
            ASSERT_EQ(out.height, 8 >> m);
            for (std::size_t i = 0; i < in.pixels.size(); ++i)
                for (int c = 0; c < 4; ++c) {
                    const float expected = (c == 3 && !fc.hasAlpha) ? 1.0f : in.pixels[i][c];
                    const float tol = (c == 3 && !fc.hasAlpha) ? 0.0f : tolerance(fc.format, c, in.pixels[i]);
                    if (std::abs(out.pixels[i][c] - expected) > tol && ++failures <= 5)
                        ADD_FAILURE() << "level " << m << " face " << f << " texel " << i << " channel " << c
                                      << ": wrote " << expected << ", read " << out.pixels[i][c]
                                      << ", tolerance " << tol;
                }
        }
    }
    EXPECT_EQ(failures, 0);
}

TEST_P(Ktx2Formats, HeaderFieldsAreExactlyAsSpecified) {
    const FormatCase& fc = GetParam();
    TempDir dir;
    ibl::writeKtx2Cube(dir / "cube.ktx2", randomChain(8, 4, fc.isSigned, 7), fc.format, {});
    const std::vector<std::uint8_t> b = readBytes(dir / "cube.ktx2");
    const std::vector<std::uint8_t> identifier = {0xAB, 0x4B, 0x54, 0x58, 0x20, 0x32,
                                                  0x30, 0xBB, 0x0D, 0x0A, 0x1A, 0x0A};
    ASSERT_GT(b.size(), 80u);
    EXPECT_TRUE(std::equal(identifier.begin(), identifier.end(), b.begin()));
    EXPECT_EQ(u32At(b, 12), fc.vkFormat);
    EXPECT_EQ(u32At(b, 16), fc.typeSize);
    EXPECT_EQ(u32At(b, 20), 8u);                          // pixelWidth
    EXPECT_EQ(u32At(b, 24), 8u);                          // pixelHeight
    EXPECT_EQ(u32At(b, 28), 0u);                          // pixelDepth
    EXPECT_EQ(u32At(b, 32), 0u);                          // layerCount
    EXPECT_EQ(u32At(b, 36), 6u);                          // faceCount
    EXPECT_EQ(u32At(b, 40), 4u);                          // levelCount
    EXPECT_EQ(u32At(b, 44), 0u);                          // supercompressionScheme
    EXPECT_EQ(u32At(b, 48), 80u + 4 * 24);                // dfdByteOffset: right after the level index
    EXPECT_EQ(u32At(b, 56), u32At(b, 48) + u32At(b, 52)); // kvdByteOffset: right after the DFD
    EXPECT_GT(u32At(b, 60), 0u);                          // kvdByteLength: at least KTXwriter
    EXPECT_EQ(u64At(b, 64), 0u);                          // sgdByteOffset
    EXPECT_EQ(u64At(b, 72), 0u);                          // sgdByteLength
}

// The basic descriptor blocks of the Khronos Data Format Specification's tables for these vkFormats:
// RGBSDA, BT709, LINEAR, straight alpha, 1x1x1x1 blocks; per sample bitOffset | (bitLength-1) << 16 |
// (channel | F 0x80 | S 0x40 | E 0x20) << 24, position 0, sampleLower, sampleUpper.
std::vector<std::uint32_t> expectedDfd(Ktx2Format format) {
    const std::uint32_t model = 1 | (1 << 8) | (1 << 16);
    const std::uint32_t minusOne = 0xBF800000u, one = 0x3F800000u;
    switch (format) {
    case Ktx2Format::RGBA16F:
        return {92,          0,           2 | (88u << 16),
                model,       0,           8,
                0,           0xC00F0000u, 0,
                minusOne,    one,         0xC10F0010u,
                0,           minusOne,    one,
                0xC20F0020u, 0,           minusOne,
                one,         0xCF0F0030u, 0,
                minusOne,    one};
    case Ktx2Format::RGBA32F:
        return {92,          0,           2 | (88u << 16),
                model,       0,           16,
                0,           0xC01F0000u, 0,
                minusOne,    one,         0xC11F0020u,
                0,           minusOne,    one,
                0xC21F0040u, 0,           minusOne,
                one,         0xCF1F0060u, 0,
                minusOne,    one};
    case Ktx2Format::B10G11R11:
        return {76, 0,   2 | (72u << 16), model, 0, 4,  0, 0x800A0000u, 0, 0, one, 0x810A000Bu, 0,
                0,  one, 0x82090016u,     0,     0, one};
    case Ktx2Format::E5B9G9R9:
        return {124,         0,           2 | (120u << 16),
                model,       0,           4,
                0,           0x00080000u, 0,
                0,           8448,        0x2004001Bu,
                0,           15,          31,
                0x01080009u, 0,           0,
                8448,        0x2104001Bu, 0,
                15,          31,          0x02080012u,
                0,           0,           8448,
                0x2204001Bu, 0,           15,
                31};
    default: // the BC6H formats: their descriptor is test_bc6h.cpp's
        break;
    }
    return {};
}

TEST_P(Ktx2Formats, DataFormatDescriptorMatchesTheFormatTable) {
    const FormatCase& fc = GetParam();
    TempDir dir;
    ibl::writeKtx2Cube(dir / "cube.ktx2", randomChain(4, 3, fc.isSigned, 7), fc.format, {});
    const std::vector<std::uint8_t> b = readBytes(dir / "cube.ktx2");
    const std::vector<std::uint32_t> expected = expectedDfd(fc.format);
    ASSERT_EQ(u32At(b, 52), 4 * expected.size()); // dfdByteLength == dfdTotalSize
    const std::size_t dfd = u32At(b, 48);
    for (std::size_t i = 0; i < expected.size(); ++i)
        EXPECT_EQ(u32At(b, dfd + 4 * i), expected[i]) << "DFD word " << i;
}

TEST_P(Ktx2Formats, LevelsAreAlignedOrderedSmallestFirstAndInsideTheFile) {
    const FormatCase& fc = GetParam();
    TempDir dir;
    ibl::writeKtx2Cube(dir / "cube.ktx2", randomChain(8, 4, fc.isSigned, 7), fc.format, {{"a", "odd"}});
    const std::vector<std::uint8_t> b = readBytes(dir / "cube.ktx2");
    const std::uint64_t alignment = std::max<std::uint32_t>(fc.texelBytes, 4); // lcm(texel size, 4)
    const std::uint64_t kvdEnd = std::uint64_t(u32At(b, 56)) + u32At(b, 60);
    std::uint64_t previousEnd = kvdEnd;
    for (int p = 3; p >= 0; --p) { // file order: smallest level first
        const std::size_t entry = 80 + 24 * std::size_t(p);
        const std::uint64_t offset = u64At(b, entry), length = u64At(b, entry + 8);
        const std::uint64_t size = std::uint64_t(8 >> p);
        EXPECT_EQ(length, 6 * size * size * fc.texelBytes) << "level " << p;
        EXPECT_EQ(u64At(b, entry + 16), length) << "uncompressedByteLength of level " << p;
        EXPECT_EQ(offset % alignment, 0u) << "level " << p;
        EXPECT_GE(offset, previousEnd) << "level " << p;
        EXPECT_LT(offset - previousEnd, alignment) << "mipPadding of level " << p;
        ASSERT_LE(offset + length, b.size()) << "level " << p;
        for (std::uint64_t i = previousEnd; i < offset; ++i)
            EXPECT_EQ(b[i], 0) << "padding byte " << i;
        previousEnd = offset + length;
    }
    EXPECT_EQ(previousEnd, b.size()); // level 0 ends the file
}

TEST_P(Ktx2Formats, ClampsToTheFormatRangeAndCountsClampedTexels) {
    const FormatCase& fc = GetParam();
    TempDir dir;
    ibl::ImageRGBA image(4, 1);
    image.pixels = {{1e6f, 1.0f, 2.0f, 1.0f},
                    {-1e6f, 3.0f, 1e6f, 1.0f},
                    {4.0f, 5.0f, 6.0f, 0.5f},
                    {-2.0f, 1.0f, 1.0f, 1.0f}};
    const ibl::Ktx2WriteStats stats = ibl::writeKtx2Image(dir / "lut.ktx2", image, fc.format, {});
    const ibl::Ktx2Image back = ibl::readKtx2(dir / "lut.ktx2");
    ASSERT_EQ(back.levels.size(), 1u);
    const std::vector<glm::vec4>& px = back.levels[0][0].pixels;
    EXPECT_EQ(stats.repairedNonFinite, 0u);
    switch (fc.format) {
    case Ktx2Format::RGBA16F:
        EXPECT_EQ(stats.clampedTexels, 2u);
        EXPECT_EQ(px[0].r, 65504.0f);
        EXPECT_EQ(px[1].r, -65504.0f);
        EXPECT_EQ(px[1].b, 65504.0f);
        EXPECT_EQ(px[3].r, -2.0f);
        break;
    case Ktx2Format::RGBA32F:
        EXPECT_EQ(stats.clampedTexels, 0u);
        EXPECT_EQ(px[0].r, 1e6f);
        EXPECT_EQ(px[1].r, -1e6f);
        break;
    case Ktx2Format::B10G11R11:
        EXPECT_EQ(stats.clampedTexels, 3u); // texel 3 clamps its negative red to 0
        EXPECT_EQ(px[0].r, 65024.0f);
        EXPECT_EQ(px[1].r, 0.0f);
        EXPECT_EQ(px[1].b, 64512.0f);
        EXPECT_EQ(px[3].r, 0.0f);
        break;
    case Ktx2Format::E5B9G9R9:
        EXPECT_EQ(stats.clampedTexels, 3u);
        EXPECT_EQ(px[0].r, 65408.0f);
        EXPECT_EQ(px[1].r, 0.0f);
        EXPECT_EQ(px[1].b, 65408.0f);
        EXPECT_EQ(px[3].r, 0.0f);
        break;
    default: // the BC6H formats refuse negative texels (test_bc6h.cpp)
        break;
    }
    EXPECT_EQ(px[2].g, 5.0f); // representable in every format: untouched
}

TEST_P(Ktx2Formats, NonFiniteValuesAreRepairedAndNeverStored) {
    const FormatCase& fc = GetParam();
    TempDir dir;
    ibl::ImageRGBA image(5, 1);
    image.pixels = {{NAN, 1.0f, 1.0f, 1.0f},
                    {INFINITY, 1.0f, 1.0f, 1.0f},
                    {-INFINITY, 1.0f, 1.0f, 1.0f},
                    {1.0f, 2.0f, 3.0f, NAN}, // alpha: stored (and repaired) only by formats with alpha
                    {1.0f, 2.0f, 3.0f, 1.0f}};
    const ibl::Ktx2WriteStats stats = ibl::writeKtx2Image(dir / "lut.ktx2", image, fc.format, {});
    EXPECT_EQ(stats.repairedNonFinite, fc.hasAlpha ? 4u : 3u);
    const ibl::Ktx2Image back = ibl::readKtx2(dir / "lut.ktx2");
    const std::vector<glm::vec4>& px = back.levels[0][0].pixels;
    for (const glm::vec4& p : px)
        for (int c = 0; c < 4; ++c)
            EXPECT_TRUE(std::isfinite(p[c])) << p[c];
    EXPECT_EQ(px[0].r, 0.0f);                          // NaN -> 0
    EXPECT_GT(px[1].r, 60000.0f);                      // +Inf -> the format's maximum
    EXPECT_EQ(px[2].r, fc.isSigned ? -px[1].r : 0.0f); // -Inf -> minimum (0 when unsigned)
    if (fc.hasAlpha) {
        EXPECT_EQ(px[3].a, 0.0f);
    }
}

TEST_P(Ktx2Formats, TwoDimensionalNonSquareImageRoundTrips) {
    const FormatCase& fc = GetParam();
    TempDir dir;
    ibl::ImageRGBA image(16, 8);
    for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 16; ++x)
            image.at(x, y) = {(x + 1) / 16.0f, (y + 1) / 8.0f, 0.25f, 0.5f};
    ibl::writeKtx2Image(dir / "lut.ktx2", image, fc.format, {});
    const ibl::Ktx2Image back = ibl::readKtx2(dir / "lut.ktx2");
    EXPECT_EQ(back.faceCount, 1u);
    EXPECT_EQ(back.levelCount, 1u);
    EXPECT_EQ(back.pixelWidth, 16u);
    EXPECT_EQ(back.pixelHeight, 8u);
    ASSERT_EQ(back.levels.size(), 1u);
    ASSERT_EQ(back.levels[0].size(), 1u);
    const ibl::ImageRGBA& out = back.levels[0][0];
    ASSERT_EQ(out.width, 16);
    ASSERT_EQ(out.height, 8);
    for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 16; ++x)
            for (int c = 0; c < 3; ++c)
                EXPECT_NEAR(out.at(x, y)[c], image.at(x, y)[c], tolerance(fc.format, c, image.at(x, y)))
                    << x << "," << y << " channel " << c;
}

// --- rounding ---------------------------------------------------------------------------------------------

// The value of a 5-bit-exponent small float code with `mantissaBits` mantissa bits (bias 15).
double smallFloatValue(std::uint32_t code, int mantissaBits) {
    const std::uint32_t e = code >> mantissaBits, m = code & ((1u << mantissaBits) - 1);
    return e == 0 ? std::ldexp(double(m), -14 - mantissaBits)
                  : std::ldexp(double(m + (1u << mantissaBits)), int(e) - 15 - mantissaBits);
}

// For each pair of adjacent finite codes: the exact midpoint must go to the even code, values one fp32 ulp
// either side to the nearer code, and the codes themselves must be exact.
struct RoundingCase {
    float input;
    float expected;
};

std::vector<RoundingCase> midpointCases(int mantissaBits) {
    std::vector<RoundingCase> cases;
    const std::uint32_t largest = (31u << mantissaBits) - 1; // largest finite code
    for (std::uint32_t code = 0; code < largest; ++code) {
        const float lo = float(smallFloatValue(code, mantissaBits));
        const float hi = float(smallFloatValue(code + 1, mantissaBits));
        const float mid = float((double(lo) + double(hi)) / 2); // exact: one more significant bit
        const float even = (code & 1) ? hi : lo;
        cases.push_back({lo, lo});
        cases.push_back({mid, even});
        cases.push_back({std::nextafter(mid, INFINITY), hi});
        cases.push_back({std::nextafter(mid, 0.0f), lo});
    }
    return cases;
}

TEST(Ktx2Rounding, HalfRoundsToNearestEvenAtEveryMidpoint) {
    TempDir dir;
    std::vector<RoundingCase> cases = midpointCases(10);
    const std::size_t positive = cases.size();
    for (std::size_t i = 0; i < positive; ++i)
        cases.push_back({-cases[i].input, -cases[i].expected});
    const int width = 256;
    const int height = int((cases.size() + 4 * width - 1) / (4 * width));
    ibl::ImageRGBA image(width, height);
    for (std::size_t i = 0; i < cases.size(); ++i)
        image.pixels[i / 4][int(i % 4)] = cases[i].input;
    ibl::writeKtx2Image(dir / "half.ktx2", image, Ktx2Format::RGBA16F, {});
    const ibl::Ktx2Image back = ibl::readKtx2(dir / "half.ktx2");
    int failures = 0;
    for (std::size_t i = 0; i < cases.size(); ++i) {
        const float got = back.levels[0][0].pixels[i / 4][int(i % 4)];
        if (got != cases[i].expected && ++failures <= 5)
            ADD_FAILURE() << std::hexfloat << cases[i].input << " -> " << got << ", expected "
                          << cases[i].expected;
    }
    EXPECT_EQ(failures, 0) << "of " << cases.size();
}

#ifdef __FLT16_MAX__
// Cross-check against the compiler's own float -> _Float16 conversion (round to nearest even).
TEST(Ktx2Rounding, HalfMatchesCompilerFloat16Conversion) {
    TempDir dir;
    std::mt19937 rng(99);
    std::uniform_real_distribution<float> logValue(-26.0f, 15.99f);
    ibl::ImageRGBA image(256, 256);
    for (glm::vec4& p : image.pixels)
        for (int c = 0; c < 4; ++c)
            p[c] = std::exp2(logValue(rng)) * ((rng() & 1) ? -1.0f : 1.0f);
    ibl::writeKtx2Image(dir / "half.ktx2", image, Ktx2Format::RGBA16F, {});
    const ibl::Ktx2Image back = ibl::readKtx2(dir / "half.ktx2");
    int failures = 0;
    for (std::size_t i = 0; i < image.pixels.size(); ++i)
        for (int c = 0; c < 4; ++c) {
            const float in = image.pixels[i][c];
            const float expected = std::clamp(float(_Float16(in)), -65504.0f, 65504.0f);
            if (back.levels[0][0].pixels[i][c] != expected && ++failures <= 5)
                ADD_FAILURE() << std::hexfloat << in << " -> " << back.levels[0][0].pixels[i][c]
                              << ", expected " << expected;
        }
    EXPECT_EQ(failures, 0);
}
#endif

TEST(Ktx2Rounding, B10G11R11RoundsToNearestEvenAtEveryMidpoint) {
    TempDir dir;
    const std::vector<RoundingCase> red = midpointCases(6);  // 11-bit floats, tested in R
    const std::vector<RoundingCase> blue = midpointCases(5); // 10-bit floats, tested in B
    ibl::ImageRGBA image(int(red.size()), 1);
    for (std::size_t i = 0; i < red.size(); ++i)
        image.pixels[i] = {red[i].input, 1.0f, blue[i % blue.size()].input, 1.0f};
    const ibl::Ktx2WriteStats stats =
        ibl::writeKtx2Image(dir / "packed.ktx2", image, Ktx2Format::B10G11R11, {});
    EXPECT_EQ(stats.clampedTexels, 0u);
    const ibl::Ktx2Image back = ibl::readKtx2(dir / "packed.ktx2");
    int failures = 0;
    for (std::size_t i = 0; i < red.size(); ++i) {
        const glm::vec4& got = back.levels[0][0].pixels[i];
        if ((got.r != red[i].expected || got.b != blue[i % blue.size()].expected) && ++failures <= 5)
            ADD_FAILURE() << std::hexfloat << "R " << red[i].input << " -> " << got.r << " (expected "
                          << red[i].expected << "), B " << blue[i % blue.size()].input << " -> " << got.b
                          << " (expected " << blue[i % blue.size()].expected << ")";
    }
    EXPECT_EQ(failures, 0);
}

TEST(Ktx2Rounding, E5B9G9R9StoresRepresentableValuesExactly) {
    TempDir dir;
    ibl::ImageRGBA image(5, 1);
    // Each texel's channels share one exponent and fit in 9 bits of mantissa at that exponent.
    image.pixels = {{1.0f, 0.5f, 0.25f, 1.0f},
                    {65408.0f, 128.0f, 0.0f, 1.0f},
                    {std::ldexp(511.0f, -24), std::ldexp(1.0f, -24), 0.0f, 1.0f},
                    {3.0f, 1.5f, 0.0078125f, 1.0f},
                    {0.0f, 0.0f, 0.0f, 1.0f}};
    ibl::writeKtx2Image(dir / "rgb9e5.ktx2", image, Ktx2Format::E5B9G9R9, {});
    const ibl::Ktx2Image back = ibl::readKtx2(dir / "rgb9e5.ktx2");
    for (std::size_t i = 0; i < image.pixels.size(); ++i)
        for (int c = 0; c < 3; ++c)
            EXPECT_EQ(back.levels[0][0].pixels[i][c], image.pixels[i][c]) << i << "," << c;
}

// When the largest channel's mantissa rounds up to 512 the shared exponent must grow by one (Vulkan
// shared-exponent conversion); otherwise the mantissa would overflow into the next channel's bits.
TEST(Ktx2Rounding, E5B9G9R9RoundingCarriesIntoTheSharedExponent) {
    TempDir dir;
    ibl::ImageRGBA image(1, 1);
    image.pixels = {{1023.5f, 512.0f, 0.0f, 1.0f}}; // 1023.5 / 2 rounds to mantissa 512 at exponent 2^1
    ibl::writeKtx2Image(dir / "rgb9e5.ktx2", image, Ktx2Format::E5B9G9R9, {});
    const glm::vec4 back = ibl::readKtx2(dir / "rgb9e5.ktx2").levels[0][0].pixels[0];
    EXPECT_EQ(back.r, 1024.0f);
    EXPECT_EQ(back.g, 512.0f);
    EXPECT_EQ(back.b, 0.0f);
}

// --- key/value data
// -----------------------------------------------------------------------------------------

TEST(Ktx2KeyValue, PairsAreSortedNulTerminatedPaddedAndIncludeTheWriter) {
    TempDir dir;
    const ibl::Ktx2KeyValues pairs = {
        {"zeta", "last"}, {"iblbake.ldMapping", "frostbite-eq63"}, {"Alpha", "1"}};
    ibl::writeKtx2Cube(dir / "cube.ktx2", randomChain(4, 3, true, 3), Ktx2Format::RGBA16F, pairs);
    const std::vector<std::uint8_t> b = readBytes(dir / "cube.ktx2");
    const std::size_t kvd = u32At(b, 56), kvdLength = u32At(b, 60);
    ASSERT_EQ(kvd % 4, 0u);
    std::vector<std::pair<std::string, std::string>> entries;
    std::size_t at = kvd;
    while (at < kvd + kvdLength) {
        const std::uint32_t length = u32At(b, at);
        const std::string keyAndValue(b.begin() + std::ptrdiff_t(at + 4),
                                      b.begin() + std::ptrdiff_t(at + 4 + length));
        const std::size_t nul = keyAndValue.find('\0');
        ASSERT_NE(nul, std::string::npos);
        ASSERT_EQ(keyAndValue.back(), '\0')
            << "value of " << keyAndValue.substr(0, nul) << " not NUL-terminated";
        entries.emplace_back(keyAndValue.substr(0, nul), keyAndValue.substr(nul + 1, length - nul - 2));
        const std::size_t padded = (length + 3) / 4 * 4;
        for (std::size_t i = length; i < padded; ++i)
            EXPECT_EQ(b[at + 4 + i], 0) << "valuePadding";
        at += 4 + padded;
    }
    EXPECT_EQ(at, kvd + kvdLength); // kvdByteLength covers all entries and their padding
    const std::vector<std::pair<std::string, std::string>> expected = {
        {"Alpha", "1"},
        {"KTXwriter", std::string("iblbake ") + IBLBAKE_VERSION},
        {"iblbake.ldMapping", "frostbite-eq63"},
        {"zeta", "last"}};
    EXPECT_EQ(entries, expected); // sorted by code point: 'A' < 'K' < 'i' < 'z'

    const ibl::Ktx2Image back = ibl::readKtx2(dir / "cube.ktx2");
    EXPECT_EQ(back.keyValues, (std::map<std::string, std::string>(expected.begin(), expected.end())));
}

TEST(Ktx2KeyValue, ReservedEmptyOrDuplicateKeysAreRejectedBeforeWriting) {
    TempDir dir;
    const ibl::CubeMapChain chain = randomChain(4, 1, true, 3);
    for (const ibl::Ktx2KeyValues& bad :
         {ibl::Ktx2KeyValues{{"KTXwriter", "me"}}, ibl::Ktx2KeyValues{{"", "x"}},
          ibl::Ktx2KeyValues{{"a", "1"}, {"a", "2"}}})
        EXPECT_THROW(ibl::writeKtx2Cube(dir / "cube.ktx2", chain, Ktx2Format::RGBA16F, bad), ibl::Error);
    EXPECT_TRUE(filesIn(dir.path()).empty());
}

// --- writer failures
// ------------------------------------------------------------------------------------------

TEST(Ktx2Writer, MissingDirectoryThrowsNamingTheFileAndLeavesNothing) {
    TempDir dir;
    const fs::path target = dir / "missing" / "cube.ktx2";
    try {
        ibl::writeKtx2Cube(target, randomChain(4, 3, true, 3), Ktx2Format::RGBA16F, {});
        ADD_FAILURE() << "no exception";
    } catch (const ibl::Error& e) {
        EXPECT_NE(std::string(e.what()).find(target.string()), std::string::npos) << e.what();
    }
    EXPECT_FALSE(fs::exists(dir / "missing"));
    EXPECT_TRUE(filesIn(dir.path()).empty());
}

TEST(Ktx2Writer, InvalidChainThrowsAndKeepsTheExistingFile) {
    TempDir dir;
    const fs::path target = dir / "cube.ktx2";
    writeBytes(target, {'o', 'l', 'd'});
    ibl::CubeMapChain wrongLevelSize = randomChain(8, 3, true, 3);
    wrongLevelSize.levels[2] = ibl::CubeMap(3);
    ibl::CubeMapChain tooManyLevels = randomChain(8, 4, true, 3);
    tooManyLevels.levels.push_back(ibl::CubeMap(1));
    ibl::CubeMapChain wrongFace = randomChain(8, 2, true, 3);
    wrongFace.levels[1].faces[4] = ibl::ImageRGBA(4, 2);
    for (const ibl::CubeMapChain* chain : {&wrongLevelSize, &tooManyLevels, &wrongFace}) {
        try {
            ibl::writeKtx2Cube(target, *chain, Ktx2Format::RGBA16F, {});
            ADD_FAILURE() << "no exception";
        } catch (const ibl::Error& e) {
            EXPECT_EQ(std::string(e.what()).rfind(target.string() + ": ", 0), 0u) << e.what();
        }
    }
    EXPECT_THROW(ibl::writeKtx2Cube(target, ibl::CubeMapChain{}, Ktx2Format::RGBA16F, {}), ibl::Error);
    EXPECT_EQ(readBytes(target), (std::vector<std::uint8_t>{'o', 'l', 'd'}));
    EXPECT_EQ(filesIn(dir.path()), std::vector<std::string>{"cube.ktx2"});
}

// A write that fails half-way (here: the file size limit, EFBIG) must leave the old file and no temporary.
TEST(Ktx2Writer, WriteFailingMidwayKeepsTheExistingFile) {
    TempDir dir;
    const fs::path target = dir / "cube.ktx2";
    writeBytes(target, {'o', 'l', 'd'});
    struct rlimit saved {};
    ASSERT_EQ(::getrlimit(RLIMIT_FSIZE, &saved), 0);
    if (saved.rlim_max != RLIM_INFINITY && saved.rlim_max < 4096) GTEST_SKIP() << "file size limit too low";
    const auto previousHandler = std::signal(SIGXFSZ, SIG_IGN); // get EFBIG instead of a signal
    struct rlimit limited = saved;
    limited.rlim_cur = 2048; // the metadata and the small levels fit, level 1 (3 KiB) does not
    ASSERT_EQ(::setrlimit(RLIMIT_FSIZE, &limited), 0);
    std::string message;
    try {
        ibl::writeKtx2Cube(target, randomChain(16, 5, true, 3), Ktx2Format::RGBA16F, {});
    } catch (const ibl::Error& e) {
        message = e.what();
    }
    ::setrlimit(RLIMIT_FSIZE, &saved);
    std::signal(SIGXFSZ, previousHandler);
    EXPECT_EQ(message.rfind(target.string() + ": ", 0), 0u) << "message: " << message;
    EXPECT_EQ(readBytes(target), (std::vector<std::uint8_t>{'o', 'l', 'd'}));
    EXPECT_EQ(filesIn(dir.path()), std::vector<std::string>{"cube.ktx2"});
}

// --- damaged input
// ---------------------------------------------------------------------------------------------

TEST(Ktx2Reader, MissingOrEmptyFileThrows) {
    TempDir dir;
    EXPECT_TRUE(rejects(dir / "absent.ktx2"));
    writeBytes(dir / "empty.ktx2", {});
    EXPECT_TRUE(rejects(dir / "empty.ktx2"));
    EXPECT_TRUE(rejects(dir.path())); // a directory
}

TEST(Ktx2Reader, EveryTruncationThrows) {
    TempDir dir;
    const fs::path good = dir / "good.ktx2";
    ibl::writeKtx2Cube(good, randomChain(8, 4, true, 5), Ktx2Format::RGBA16F, {{"key", "value"}});
    const std::vector<std::uint8_t> bytes = readBytes(good);
    ASSERT_NO_THROW(ibl::readKtx2(good));
    const fs::path cut = dir / "cut.ktx2";
    int accepted = 0;
    for (std::size_t length = 0; length < bytes.size(); ++length) {
        writeBytes(cut, std::vector<std::uint8_t>(bytes.begin(), bytes.begin() + std::ptrdiff_t(length)));
        if (!rejects(cut) && ++accepted <= 5)
            ADD_FAILURE() << "truncated to " << length << " bytes was accepted";
    }
    EXPECT_EQ(accepted, 0);
}

std::vector<std::uint8_t> flipped(std::vector<std::uint8_t> bytes, std::size_t byte, int bit) {
    bytes.at(byte) ^= std::uint8_t(1u << bit);
    return bytes;
}

TEST(Ktx2Reader, BitFlippedHeaderFieldsThrow) {
    TempDir dir;
    const fs::path good = dir / "good.ktx2";
    ibl::writeKtx2Cube(good, randomChain(8, 4, true, 5), Ktx2Format::RGBA16F, {{"key", "value"}});
    const std::vector<std::uint8_t> bytes = readBytes(good);
    const std::size_t dfd = u32At(bytes, 48), kvd = u32At(bytes, 56);
    struct Flip {
        std::size_t byte;
        int bit;
        const char* what;
    };
    const Flip flips[] = {
        {0, 7, "identifier"},
        {5, 0, "identifier"},
        {11, 1, "identifier"},
        {12, 0, "vkFormat"},
        {12, 4, "vkFormat"},
        {16, 0, "typeSize"},
        {20, 0, "pixelWidth"},
        {23, 7, "pixelWidth"},
        {26, 0, "pixelHeight"},
        {28, 0, "pixelDepth"},
        {32, 1, "layerCount"}, // 0 -> 2 (0 -> 1: OneLayerCubeArrayHoldsTheSameCube)
        {36, 0, "faceCount"},
        {36, 2, "faceCount"},
        {40, 2, "levelCount"},
        {43, 7, "levelCount"},
        {44, 0, "supercompression"},
        {48, 2, "dfdByteOffset"},
        {52, 2, "dfdByteLength"},
        {56, 3, "kvdByteOffset"},
        {60, 2, "kvdByteLength"},
        {63, 7, "kvdByteLength"},
        {64, 0, "sgdByteOffset"},
        {77, 1, "sgdByteLength"},
        {80, 0, "level 0 byteOffset"},
        {87, 7, "level 0 byteOffset"},
        {88, 1, "level 0 byteLength"},
        {103, 6, "level 0 uncompressed"},
        {152, 5, "level 3 byteOffset"},
        {dfd + 12, 0, "colorModel"},
        {dfd + 20, 2, "bytesPlane0"},
        {dfd + 30, 0, "sample bitLength"},
        {dfd + 40, 3, "sampleUpper"},
        {kvd + 3, 6, "kv length"},
    };
    const fs::path bad = dir / "bad.ktx2";
    for (const Flip& f : flips) {
        writeBytes(bad, flipped(bytes, f.byte, f.bit));
        EXPECT_TRUE(rejects(bad)) << f.what << " (byte " << f.byte << " bit " << f.bit << ")";
    }
}

// Every single-bit flip of the header, index and level index is detected; flips in the DFD and key/value
// data either are detected or leave a valid file (e.g. another metadata value) — never a crash or a
// different exception type.
TEST(Ktx2Reader, EverySingleBitFlipOfTheMetadataIsHandled) {
    TempDir dir;
    const fs::path good = dir / "good.ktx2";
    ibl::writeKtx2Cube(good, randomChain(4, 3, true, 5), Ktx2Format::E5B9G9R9, {{"key", "value"}});
    const std::vector<std::uint8_t> bytes = readBytes(good);
    const std::size_t indexEnd = 80 + 3 * 24;
    const std::size_t metadataEnd = std::size_t(u32At(bytes, 56)) + u32At(bytes, 60);
    const fs::path bad = dir / "bad.ktx2";
    int undetectedInIndex = 0;
    for (std::size_t byte = 0; byte < metadataEnd; ++byte)
        for (int bit = 0; bit < 8; ++bit) {
            if (byte == 32 && bit == 0) continue; // layerCount 0 -> 1: OneLayerCubeArrayHoldsTheSameCube
            writeBytes(bad, flipped(bytes, byte, bit));
            try {
                ibl::readKtx2(bad);
                if (byte < indexEnd && ++undetectedInIndex <= 5)
                    ADD_FAILURE() << "flip of byte " << byte << " bit " << bit << " was accepted";
            } catch (const ibl::Error&) {
            }
        }
    EXPECT_EQ(undetectedInIndex, 0);
}

// The one header flip no reader can detect: layerCount 0 -> 1 makes a cube map a cube map array of one
// layer, a valid KTX2 file of the same size; it reads as the same images, so nothing is misread.
TEST(Ktx2Reader, OneLayerCubeArrayHoldsTheSameCube) {
    TempDir dir;
    const fs::path good = dir / "good.ktx2";
    ibl::writeKtx2Cube(good, randomChain(4, 3, true, 5), Ktx2Format::E5B9G9R9, {{"key", "value"}});
    const fs::path oneLayer = dir / "one_layer.ktx2";
    writeBytes(oneLayer, flipped(readBytes(good), 32, 0));
    const ibl::Ktx2Image a = ibl::readKtx2(good), b = ibl::readKtx2(oneLayer);
    EXPECT_EQ(b.layerCount, 1u);
    EXPECT_EQ(b.faceCount, 6u);
    ASSERT_EQ(a.levels.size(), b.levels.size());
    for (std::size_t m = 0; m < a.levels.size(); ++m)
        for (std::size_t f = 0; f < 6; ++f)
            EXPECT_EQ(a.levels[m].at(f).pixels, b.levels[m].at(f).pixels) << m << " " << f;
}

// A level moved by 4 bytes into its mipPadding is still inside the file and after the metadata, but no
// longer aligned to lcm(16, 4) = 16 bytes for RGBA32F.
TEST(Ktx2Reader, MisalignedLevelIsRejected) {
    TempDir dir;
    const fs::path good = dir / "good.ktx2";
    ibl::writeKtx2Image(good, ibl::ImageRGBA(2, 2), Ktx2Format::RGBA32F, {{"a", "b"}});
    const std::vector<std::uint8_t> bytes = readBytes(good);
    const std::uint64_t kvdEnd = std::uint64_t(u32At(bytes, 56)) + u32At(bytes, 60);
    const std::uint64_t offset = u64At(bytes, 80);
    ASSERT_GE(offset - kvdEnd, 4u) << "the layout has no mipPadding to move the level into";
    std::vector<std::uint8_t> moved(bytes.begin(), bytes.begin() + std::ptrdiff_t(offset - 4));
    moved.insert(moved.end(), bytes.begin() + std::ptrdiff_t(offset), bytes.end());
    for (int i = 0; i < 8; ++i)
        moved[80 + i] = std::uint8_t((offset - 4) >> (8 * i));
    const fs::path bad = dir / "bad.ktx2";
    writeBytes(bad, moved);
    EXPECT_TRUE(rejects(bad));
}

TEST(Ktx2Reader, AbsurdSizesAreRejectedWithoutAllocating) {
    TempDir dir;
    const fs::path good = dir / "good.ktx2";
    ibl::writeKtx2Image(good, ibl::ImageRGBA(4, 4), Ktx2Format::RGBA32F, {});
    std::vector<std::uint8_t> bytes = readBytes(good);
    const fs::path bad = dir / "bad.ktx2";
    // pixelWidth = pixelHeight = 2^31 - 1, and a level 0 entry whose byte lengths claim 2^64 - 1 bytes
    // (the saturated size of such a level).
    std::vector<std::uint8_t> huge = bytes;
    const std::uint8_t intMax[4] = {0xFF, 0xFF, 0xFF, 0x7F};
    std::copy(intMax, intMax + 4, huge.begin() + 20);       // pixelWidth
    std::copy(intMax, intMax + 4, huge.begin() + 24);       // pixelHeight
    std::fill(huge.begin() + 88, huge.begin() + 104, 0xFF); // byteLength, uncompressedByteLength
    writeBytes(bad, huge);
    EXPECT_TRUE(rejects(bad));
    // levelCount huge.
    std::vector<std::uint8_t> levels = bytes;
    std::fill(levels.begin() + 40, levels.begin() + 44, 0xFF);
    writeBytes(bad, levels);
    EXPECT_TRUE(rejects(bad));
}

} // namespace

// A cube whose texels hold their own direction, for the layout of the three profile.
ibl::CubeMapChain directionCube(int n) {
    ibl::CubeMapChain chain;
    ibl::CubeMap level;
    level.faceSize = n;
    for (int f = 0; f < 6; ++f) {
        level.faces[std::size_t(f)] = ibl::ImageRGBA(n, n);
        for (int y = 0; y < n; ++y)
            for (int x = 0; x < n; ++x)
                level.faces[std::size_t(f)].pixels[std::size_t(y * n + x)] =
                    glm::vec4(ibl::cubeTexelDirection(f, uint32_t(x), uint32_t(y), uint32_t(n)), 1.0f);
    }
    chain.levels.push_back(level);
    return chain;
}

// --profile three stores the cube mirrored in x (three.js samples a CubeTexture at (-x, y, z)); readKtx2
// gives the standard layout back, so iblbake's readers see one convention.
TEST(Ktx2CubeProfile, ThreeStoresTheCubeMirroredInXAndReadsBackStandard) {
    TempDir dir;
    const int n = 8;
    const ibl::CubeMapChain chain = directionCube(n);
    ibl::writeKtx2Cube(dir / "three.ktx2", chain, ibl::Ktx2Format::RGBA32F,
                       {{ibl::kCubeProfileKey, "three"}});
    const ibl::Ktx2Image back = ibl::readKtx2(dir / "three.ktx2");
    EXPECT_EQ(back.keyValues.at(ibl::kCubeProfileKey), "three");
    for (int f = 0; f < 6; ++f)
        EXPECT_EQ(back.levels[0][std::size_t(f)].pixels, chain.levels[0].faces[std::size_t(f)].pixels) << f;

    // As stored (the key renamed, same length, so the reader leaves the layout alone): the texel through
    // which three looks along d holds our direction (-d.x, d.y, d.z).
    std::ifstream in(dir / "three.ktx2", std::ios::binary);
    std::vector<std::uint8_t> bytes((std::istreambuf_iterator<char>(in)), {});
    const std::string key = ibl::kCubeProfileKey;
    auto at = std::search(bytes.begin(), bytes.end(), key.begin(), key.end());
    ASSERT_NE(at, bytes.end());
    *(at + std::ptrdiff_t(key.size()) - 1) = 'X';
    const ibl::Ktx2Image stored = ibl::parseKtx2(bytes, "three.ktx2");
    for (int f = 0; f < 6; ++f)
        for (int y = 0; y < n; ++y)
            for (int x = 0; x < n; ++x) {
                const glm::vec3 d = ibl::cubeTexelDirection(f, uint32_t(x), uint32_t(y), uint32_t(n));
                const glm::vec4 texel = stored.levels[0][std::size_t(f)].pixels[std::size_t(y * n + x)];
                EXPECT_NEAR(texel.x, -d.x, 1e-6f);
                EXPECT_NEAR(texel.y, d.y, 1e-6f);
                EXPECT_NEAR(texel.z, d.z, 1e-6f);
            }
    EXPECT_THROW(ibl::writeKtx2Cube(dir / "bad.ktx2", chain, ibl::Ktx2Format::RGBA32F,
                                    {{ibl::kCubeProfileKey, "unity"}}),
                 ibl::Error);
}
