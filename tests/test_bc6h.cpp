// BC6H (unsigned) encoder and decoder (baker/src/io/bc6h.h): the mode layouts fill a block exactly, a block
// built by hand decodes to the values the specification's formulas give, our decoder agrees with
// OpenImageIO's DDS reader (a decoder we did not write) on random blocks of every mode and on our encoder's
// output, and the encoder's error stays within its bounds on smooth and on sharp content.
#include "iblbake/core/error.h"
#include "iblbake/ktx2/dds.h"
#include "iblbake/ktx2/ktx2.h"

#include "cli_runner.h"

#include <bc6h.h>
#include <bc6h_layout.h>
#include <small_float.h>

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>
#include <random>
#include <set>

namespace {

namespace fs = std::filesystem;
using namespace ibl::bc6h;

// Every mode's mode bits, endpoint fields, partition and index bits add up to 128, no field bit is stored
// twice, and every bit the mode's precision needs is stored.
TEST(Bc6hLayout, EveryModeFillsTheBlockOnce) {
    for (const Mode& mode : kModes) {
        std::set<std::pair<int, int>> stored;
        int bits = mode.modeBits;
        for (const BitRun& r : mode.runs) {
            if (isEnd(r)) break;
            const int step = r.first <= r.last ? 1 : -1;
            for (int b = r.first;; b += step) {
                EXPECT_TRUE(stored.insert({r.field, b}).second) << "mode " << int(mode.number);
                ++bits;
                if (b == r.last) break;
            }
        }
        bits += mode.regions == 2 ? 5 + 46 : 63;
        EXPECT_EQ(bits, 128) << "mode " << int(mode.number);
        for (int e = 0; e < 2 * mode.regions; ++e)
            for (int c = 0; c < 3; ++c) {
                const int needed = e == 0 ? mode.endpointBits : mode.deltaBits[std::size_t(c)];
                for (int b = 0; b < needed; ++b)
                    EXPECT_TRUE(stored.count({fieldOf(e, c), b}))
                        << "mode " << int(mode.number) << " field " << fieldOf(e, c) << " bit " << b;
            }
    }
}

// Mode 11 (code 00011) with endpoint 0 = 0x3FF and endpoint 1 = 0 in every channel and texel i holding index
// i. unquantize(0x3FF, 10) = 0xFFFF, unquantize(0, 10) = 0; texel 1 (weight 4): (65535 x 60 + 32) >> 6 =
// 61439, finish_unquantize: 61439 x 31 >> 6 = 29759 = 0x743F; texel 7 (weight 30): (65535 x 34 + 32) >> 6 =
// 34815, x 31 >> 6 = 16863 = 0x41DF; texel 15 (weight 64): 0; texel 0: 0xFFFF x 31 >> 6 = 0x7BFF.
TEST(Bc6hDecode, HandBuiltBlockGivesTheSpecificationsValues) {
    Bits128 bits;
    int position = 0;
    auto put = [&](int value, int count) {
        for (int b = 0; b < count; ++b)
            bits.set(position++, value >> b & 1);
    };
    put(0x03, 5);
    for (int c = 0; c < 3; ++c)
        put(0x3FF, 10);
    put(0, 30);
    for (int i = 0; i < 16; ++i)
        put(i, i == 0 ? 3 : 4);
    ASSERT_EQ(position, 128);
    std::uint8_t block[16];
    for (int i = 0; i < 16; ++i)
        block[i] = std::uint8_t(bits.word[i / 8] >> (8 * (i % 8)));
    const BlockHalves texels = decodeBlock(block);
    EXPECT_EQ(texels[0][0], 0x7BFF);
    EXPECT_EQ(texels[1][1], 0x743F);
    EXPECT_EQ(texels[7][2], 0x41DF);
    EXPECT_EQ(texels[15][0], 0);
    // A reserved mode (10011) decodes to 0.
    block[0] = 0x13;
    for (const auto& t : decodeBlock(block))
        EXPECT_EQ(t[0] + t[1] + t[2], 0);
}

// A DDS file (DX10 header, DXGI_FORMAT_BC6H_UF16, one 2D image) holding `blocks` as written, for
// OpenImageIO to decode.
void writeRawDds(const fs::path& file, int width, int height, const std::vector<std::uint8_t>& blocks) {
    std::vector<std::uint32_t> words = {0x20534444,
                                        124,
                                        0x1 | 0x2 | 0x4 | 0x1000 | 0x80000,
                                        std::uint32_t(height),
                                        std::uint32_t(width),
                                        std::uint32_t(blocks.size()),
                                        0,
                                        1};
    words.resize(words.size() + 11, 0);
    for (std::uint32_t w :
         {32u, 0x4u, 0x30315844u, 0u, 0u, 0u, 0u, 0u, 0x1000u, 0u, 0u, 0u, 0u, 95u, 3u, 0u, 1u, 0u})
        words.push_back(w);
    std::ofstream out(file, std::ios::binary);
    out.write(reinterpret_cast<const char*>(words.data()), std::streamsize(4 * words.size()));
    out.write(reinterpret_cast<const char*>(blocks.data()), std::streamsize(blocks.size()));
}

// The RGB OpenImageIO decodes from a file's first subimage and level (or `miplevel`), as floats.
std::vector<float> oiioPixels(const fs::path& file, int& width, int& height, int subimage = 0,
                              int miplevel = 0) {
    auto in = OIIO::ImageInput::open(file.string());
    if (!in) throw std::runtime_error("OpenImageIO cannot open " + file.string() + ": " + OIIO::geterror());
    if (!in->seek_subimage(subimage, miplevel)) throw std::runtime_error("no such subimage or level");
    const OIIO::ImageSpec& spec = in->spec();
    width = spec.width;
    height = spec.height;
    std::vector<float> pixels(std::size_t(spec.width) * std::size_t(spec.height) * 3);
    if (!in->read_image(subimage, miplevel, 0, 3, OIIO::TypeDesc::FLOAT, pixels.data()))
        throw std::runtime_error("OpenImageIO cannot read " + file.string() + ": " + in->geterror());
    return pixels;
}

fs::path tempDir(const std::string& name) {
    const fs::path dir =
        fs::temp_directory_path() / ("iblbake_bc6h_" + name + "_" + std::to_string(::getpid()));
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir;
}

// Random blocks of every mode (and the reserved codes): OpenImageIO's BC6H decoder (bcdec) and ours give the
// same half for every texel.
TEST(Bc6hDecode, AgreesWithOpenImageIoOnRandomBlocksOfEveryMode) {
    std::mt19937 rng(50);
    constexpr int blocksX = 16, blocksY = 16;
    std::vector<std::uint8_t> blocks(std::size_t(blocksX * blocksY) * 16);
    const std::array<int, 18> codes = {0x00, 0x01, 0x02, 0x06, 0x0A, 0x0E, 0x12, 0x16, 0x1A,
                                       0x1E, 0x03, 0x07, 0x0B, 0x0F, 0x13, 0x17, 0x1B, 0x1F};
    for (std::size_t b = 0; b < blocks.size() / 16; ++b) {
        for (int i = 0; i < 16; ++i)
            blocks[16 * b + std::size_t(i)] = std::uint8_t(rng());
        const int code = codes[b % codes.size()];
        const int modeBits = code < 2 ? 2 : 5;
        blocks[16 * b] = std::uint8_t((blocks[16 * b] & ~((1 << modeBits) - 1)) | code);
    }
    const fs::path dir = tempDir("random");
    writeRawDds(dir / "random.dds", 4 * blocksX, 4 * blocksY, blocks);
    int width = 0, height = 0;
    const std::vector<float> theirs = oiioPixels(dir / "random.dds", width, height);
    ASSERT_EQ(width, 4 * blocksX);
    ASSERT_EQ(height, 4 * blocksY);
    const ibl::ImageRGBA ours = decodeImage(blocks.data(), width, height);
    int differing = 0;
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x)
            for (int c = 0; c < 3; ++c) {
                const float
                    a = ours.at(x, y)[c],
                    b = theirs[(std::size_t(y) * std::size_t(width) + std::size_t(x)) * 3 + std::size_t(c)];
                if (ibl::smallfloat::floatToHalf(a) != ibl::smallfloat::floatToHalf(b) && differing++ < 5)
                    ADD_FAILURE() << "texel (" << x << ", " << y << ") channel " << c << ": ours " << a
                                  << ", OpenImageIO " << b << " (block mode code "
                                  << codes[std::size_t((y / 4) * blocksX + x / 4) % codes.size()] << ")";
            }
    EXPECT_EQ(differing, 0);
    fs::remove_all(dir);
}

// Relative error of a decoded texel against the original: sum |d - o| / sum o over RGB.
double relativeError(const glm::vec4& decoded, const glm::vec4& original) {
    double difference = 0.0, sum = 0.0;
    for (int c = 0; c < 3; ++c) {
        difference += std::fabs(double(decoded[c]) - double(original[c]));
        sum += std::fabs(double(original[c]));
    }
    return sum > 0.0 ? difference / sum : difference;
}

// 16 x 16 texels of a smooth HDR gradient (0.05 to 50 across, colour varying down) and of a sharp edge
// (a bright disk on a dim sky, 3 decades apart): mean relative errors per preset within stated bounds,
// each preset no worse than the one before (measured: smooth 2.5%, 2.3%, 2.3%; sharp 0.41%, 0.11%,
// 0.11%); a constant block at the default preset is exact.
TEST(Bc6hEncode, ErrorStaysWithinBoundsOnSmoothAndSharpContent) {
    ibl::ImageRGBA smooth(16, 16), sharp(16, 16);
    for (int y = 0; y < 16; ++y)
        for (int x = 0; x < 16; ++x) {
            const float v = 0.05f * std::pow(1000.0f, x / 15.0f);
            smooth.at(x, y) = {v, v * (0.8f + y / 80.0f), v * (1.0f - y / 40.0f), 1.0f};
            const bool disk = (x - 7.5f) * (x - 7.5f) + (y - 6.5f) * (y - 6.5f) < 12.0f;
            sharp.at(x, y) =
                disk ? glm::vec4(4000.0f, 3800.0f, 3500.0f, 1.0f) : glm::vec4(0.8f, 1.2f, 2.0f, 1.0f);
        }
    const struct {
        Preset preset;
        double smoothBound, sharpBound;
    } presets[] = {
        {Preset::Fast, 0.03, 0.006}, {Preset::Default, 0.027, 0.002}, {Preset::Best, 0.027, 0.002}};
    double previousSmooth = 1e9, previousSharp = 1e9;
    for (const auto& p : presets) {
        for (const auto* image : {&smooth, &sharp}) {
            std::vector<std::uint8_t> blocks(blockCount(16, 16) * 16);
            encodeImage(*image, p.preset, blocks.data());
            const ibl::ImageRGBA decoded = decodeImage(blocks.data(), 16, 16);
            double mean = 0.0;
            for (std::size_t i = 0; i < decoded.pixels.size(); ++i)
                mean += relativeError(decoded.pixels[i], image->pixels[i]) / double(decoded.pixels.size());
            const bool isSmooth = image == &smooth;
            EXPECT_LT(mean, isSmooth ? p.smoothBound : p.sharpBound) << "preset " << int(p.preset);
            double& previous = isSmooth ? previousSmooth : previousSharp;
            EXPECT_LE(mean, previous * 1.0001) << "preset " << int(p.preset);
            previous = mean;
        }
    }
    ibl::ImageRGBA constant(4, 4);
    for (glm::vec4& t : constant.pixels)
        t = {12.5f, 0.375f, 3000.0f, 1.0f};
    std::vector<std::uint8_t> block(16);
    encodeImage(constant, Preset::Default, block.data());
    const ibl::ImageRGBA decoded = decodeImage(block.data(), 4, 4);
    for (const glm::vec4& t : decoded.pixels)
        EXPECT_EQ(t, constant.pixels[0]);
}

// A chain of `levels` levels from `size` px faces: a smooth HDR pattern, different on every face.
ibl::CubeMapChain testChain(int size, int levels) {
    ibl::CubeMapChain chain;
    for (int m = 0; m < levels; ++m) {
        const int n = std::max(1, size >> m);
        ibl::CubeMap level;
        level.faceSize = n;
        for (int f = 0; f < 6; ++f) {
            ibl::ImageRGBA face(n, n);
            for (int y = 0; y < n; ++y)
                for (int x = 0; x < n; ++x) {
                    const float v = std::exp(1.5f * std::sin(0.3f * x + f) * std::cos(0.2f * y - m));
                    face.at(x, y) = {v, 0.8f * v + 0.1f * f, 1.5f * v, 1.0f};
                }
            level.faces[std::size_t(f)] = std::move(face);
        }
        chain.levels.push_back(std::move(level));
    }
    return chain;
}

std::vector<std::uint8_t> fileBytes(const fs::path& file) {
    std::ifstream in(file, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::uint32_t u32At(const std::vector<std::uint8_t>& bytes, std::size_t offset) {
    std::uint32_t v;
    std::memcpy(&v, bytes.data() + offset, 4);
    return v;
}

// KTX2 with BC6H (KTX 2.0 and KDF "BC6H"): vkFormat 131, typeSize 1, every level whole blocks (the 2 x 2 and
// 1 x 1 levels one block a face), a DFD of colour model 131 (KHR_DF_MODEL_BC6H), texel block 4 x 4,
// 16 bytes a plane, one 128-bit FLOAT sample; read back through our decoder within 2% mean, 5% at most.
TEST(Bc6hContainers, Ktx2HoldsBlocksWithTheirDescriptor) {
    const fs::path dir = tempDir("ktx2");
    const ibl::CubeMapChain chain = testChain(8, 4);
    const ibl::Ktx2WriteStats stats =
        ibl::writeKtx2Cube(dir / "chain.ktx2", chain, ibl::Ktx2Format::BC6H, {});
    const std::vector<std::uint8_t> bytes = fileBytes(dir / "chain.ktx2");
    EXPECT_EQ(u32At(bytes, 12), 131u); // vkFormat
    EXPECT_EQ(u32At(bytes, 16), 1u);   // typeSize
    const std::uint64_t blocksPerFace[] = {4, 1, 1, 1};
    for (int m = 0; m < 4; ++m) {
        std::uint64_t length;
        std::memcpy(&length, bytes.data() + 80 + 24 * m + 8, 8);
        EXPECT_EQ(length, 6 * 16 * blocksPerFace[m]) << "level " << m;
    }
    EXPECT_EQ(stats.gpuBytes, 6u * 16u * 7u);
    EXPECT_EQ(stats.fileBytes, bytes.size());
    const std::size_t dfd = u32At(bytes, 48);
    EXPECT_EQ(u32At(bytes, dfd + 12) & 0xFFu, 131u); // colorModel
    EXPECT_EQ(u32At(bytes, dfd + 16), 0x0303u);      // texelBlockDimension 4 x 4 x 1 x 1, minus one
    EXPECT_EQ(u32At(bytes, dfd + 20), 16u);          // bytesPlane0
    EXPECT_EQ(u32At(bytes, dfd + 28), (127u << 16) | (0x80u << 24)); // bitLength 128 - 1, FLOAT, channel 0
    EXPECT_EQ(u32At(bytes, dfd), 4u + 24u + 16u);                    // dfdTotalSize: one sample
    const ibl::Ktx2Image read = ibl::readKtx2(dir / "chain.ktx2");
    ASSERT_EQ(read.levels.size(), 4u);
    double sum = 0.0, largest = 0.0;
    int count = 0;
    for (int m = 0; m < 4; ++m)
        for (int f = 0; f < 6; ++f)
            for (std::size_t i = 0; i < read.levels[m][f].pixels.size(); ++i) {
                const double error =
                    relativeError(read.levels[m][f].pixels[i], chain.levels[m].faces[f].pixels[i]);
                sum += error;
                largest = std::max(largest, error);
                ++count;
            }
    EXPECT_LT(sum / count, 0.02);
    EXPECT_LT(largest, 0.05);
    fs::remove_all(dir);
}

// DDS (DX10 header) rewrapped from KTX2 for BC6H and rgba16f: the header fields D3D engines read, the size,
// and for BC6H level 0 of every face as OpenImageIO's DDS reader decodes them (faces stacked +X..-Z) equal to
// what our KTX2 reader returns: face f starts after the whole chain of faces 0..f-1, so this also checks the
// face-major order. (OpenImageIO 2.4 lists a DDS cube's mip levels shifted by one, 16, 16, 8, ..., so its
// levels past 0 are not compared.)
TEST(Bc6hContainers, DdsCubeChainIsReadByOpenImageIoAsOurReaderReadsTheKtx2) {
    const fs::path dir = tempDir("dds");
    const ibl::CubeMapChain chain = testChain(16, 5);
    for (const auto& [format, dxgi] :
         {std::pair{ibl::Ktx2Format::BC6H, 95u}, {ibl::Ktx2Format::RGBA16F, 10u}}) {
        ibl::writeKtx2Cube(dir / "chain.ktx2", chain, format, {});
        ibl::writeDdsFromKtx2(dir / "chain.ktx2", dir / "chain.dds");
        const std::vector<std::uint8_t> dds = fileBytes(dir / "chain.dds");
        EXPECT_EQ(u32At(dds, 0), 0x20534444u);  // "DDS "
        EXPECT_EQ(u32At(dds, 4), 124u);         // dwSize
        EXPECT_EQ(u32At(dds, 12), 16u);         // dwHeight
        EXPECT_EQ(u32At(dds, 28), 5u);          // dwMipMapCount
        EXPECT_EQ(u32At(dds, 84), 0x30315844u); // ddspf.dwFourCC "DX10"
        EXPECT_EQ(u32At(dds, 108), 0x401008u);  // dwCaps: COMPLEX | TEXTURE | MIPMAP
        EXPECT_EQ(u32At(dds, 112), 0xFE00u);    // dwCaps2: CUBEMAP and all six faces
        EXPECT_EQ(u32At(dds, 128), dxgi);       // dxgiFormat
        EXPECT_EQ(u32At(dds, 132), 3u);         // resourceDimension TEXTURE2D
        EXPECT_EQ(u32At(dds, 136), 4u);         // miscFlag TEXTURECUBE
        EXPECT_EQ(u32At(dds, 140), 1u);         // arraySize: one cube
        const ibl::Ktx2Image ours = ibl::readKtx2(dir / "chain.ktx2");
        // The texel bytes: every level's images, as in the KTX2.
        const std::size_t texelBytes =
            format == ibl::Ktx2Format::BC6H ? 6 * 16 * (16 + 4 + 1 + 1 + 1) : 6 * 8 * (256 + 64 + 16 + 4 + 1);
        EXPECT_EQ(dds.size(), 148 + texelBytes);
        // OpenImageIO 2.4 reads no DXGI float format (its DDS reader: "Unsupported compression type").
        if (format == ibl::Ktx2Format::BC6H) {
            const int m = 0;
            int width = 0, height = 0;
            const std::vector<float> theirs = oiioPixels(dir / "chain.dds", width, height);
            const int n = 16;
            ASSERT_EQ(width, n);
            ASSERT_EQ(height, 6 * n);
            for (int f = 0; f < 6; ++f)
                for (int y = 0; y < n; ++y)
                    for (int x = 0; x < n; ++x)
                        for (int c = 0; c < 3; ++c)
                            ASSERT_EQ(theirs[(std::size_t(f * n + y) * std::size_t(n) + std::size_t(x)) * 3 +
                                             std::size_t(c)],
                                      ours.levels[m][f].at(x, y)[c])
                                << "format " << dxgi << " level " << m << " face " << f << " texel (" << x
                                << ", " << y << ")";
        }
    }
    fs::remove_all(dir);
}

// bc6h stores unsigned finite halves: a negative or non-finite channel is refused in one line naming the
// file, the level and the texel, and nothing is written.
TEST(Bc6hContainers, NegativeOrNonFiniteTexelsAreRefused) {
    const fs::path dir = tempDir("refused");
    for (const float bad : {-0.5f, NAN, INFINITY}) {
        ibl::CubeMapChain chain = testChain(8, 2);
        chain.levels[1].faces[3].at(2, 1).g = bad;
        try {
            ibl::writeKtx2Cube(dir / "chain.ktx2", chain, ibl::Ktx2Format::BC6H, {});
            ADD_FAILURE() << "no error for " << bad;
        } catch (const ibl::Error& e) {
            const std::string what = e.what();
            EXPECT_NE(
                what.find(
                    "chain.ktx2: bc6h stores no negative or non-finite value; level 1 image 3 texel (2, 1) "
                    "channel G"),
                std::string::npos)
                << what;
            EXPECT_EQ(what.find('\n'), std::string::npos);
        }
        EXPECT_TRUE(fs::is_empty(dir)) << bad;
    }
    fs::remove_all(dir);
}

// `iblbake specular --format bc6h -o chain.dds` delivers the DDS, and `iblbake format-cost` measures a
// chain: BC6H's GPU bytes one eighth of rgba16f's but for the levels below 4 px (one block a face), its file
// at most a sixth, its mean error below 3% at 32 and 16 px (10% at 8 and 4 px, where the sun left in the
// sample fills blocks), above rgba16f's, rgba32f's 0; a
// file that is not a KTX2 cube chain is refused in one line.
TEST(Bc6hCli, DeliversDdsAndMeasuresTheCostOfEachFormat) {
    const fs::path dir = ibl::test::freshTempDir("bc6h_cli");
    const std::string bake = "specular " + ibl::test::kSampleHdri + " --size 32 --quality draft";
    ibl::test::CliRun r = ibl::test::runCli(bake + " --format bc6h -o " + (dir / "chain.dds").string());
    ASSERT_EQ(r.exitCode, 0) << r.err;
    int width = 0, height = 0;
    oiioPixels(dir / "chain.dds", width, height);
    EXPECT_EQ(width, 32);
    EXPECT_EQ(height, 6 * 32);
    r = ibl::test::runCli(bake + " --format rgba32f -o " + (dir / "chain.ktx2").string());
    ASSERT_EQ(r.exitCode, 0) << r.err;
    r = ibl::test::runCli("format-cost " + (dir / "chain.ktx2").string() +
                          " --formats rgba16f,rgba32f,bc6h --json");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const nlohmann::json cost = nlohmann::json::parse(r.out);
    ASSERT_EQ(cost.at("formats").size(), 3u);
    const nlohmann::json &half = cost["formats"][0], &full = cost["formats"][1], &bc6h = cost["formats"][2];
    EXPECT_EQ(bc6h.at("format"), "bc6h");
    // 32, 16, 8, 4 px: 1 byte a texel; 2 and 1 px: a block of 16 bytes a face.
    EXPECT_EQ(bc6h.at("gpuBytes").get<std::uint64_t>(), 6u * (1024 + 256 + 64 + 16 + 16 + 16));
    EXPECT_EQ(half.at("gpuBytes").get<std::uint64_t>(), 6u * 8u * (1024 + 256 + 64 + 16 + 4 + 1));
    EXPECT_LE(6 * bc6h.at("fileBytes").get<std::uint64_t>(), half.at("fileBytes").get<std::uint64_t>());
    ASSERT_EQ(bc6h.at("levels").size(), 4u);
    for (std::size_t m = 0; m < 4; ++m) {
        const double mean = bc6h["levels"][m].at("meanRelative").get<double>();
        EXPECT_LT(mean, m < 2 ? 0.03 : 0.1) << "level " << m; // 8 and 4 px: the sun spans whole blocks
        EXPECT_GT(mean, half["levels"][m].at("meanRelative").get<double>()) << "level " << m;
    }
    for (const nlohmann::json& level : full["levels"])
        EXPECT_EQ(level.at("p99Relative").get<double>(), 0.0);
    r = ibl::test::runCli("dfg --size 8 --samples 8 -o " + (dir / "lut.exr").string());
    ASSERT_EQ(r.exitCode, 0) << r.err;
    r = ibl::test::runCli("format-cost " + (dir / "lut.exr").string());
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_EQ(ibl::test::lineCount(r.err), 1) << r.err;
    fs::remove_all(dir);
}

} // namespace
