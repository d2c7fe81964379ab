// iblbake export-filament (iblbake/baker/filament_export.h): the KTX1 bytes (ktx1.h) field by field, the
// filament profile's level roughness, the files of a bake's export, and the refusals (nothing written).
#include "bake_dir_support.h"

#include <iblbake/core/error.h>
#include <iblbake/ktx2/cube_profile.h>
#include <iblbake/ktx2/ktx1.h>
#include <iblbake/ktx2/ktx2.h>
#include <iblbake/ktx2/storage_scale.h>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <sstream>

namespace fs = std::filesystem;
using ibl::test::CliRun;
using ibl::test::runCli;

namespace {

std::uint32_t u32At(const std::string& bytes, std::size_t offset) {
    std::uint32_t value = 0;
    for (int b = 3; b >= 0; --b)
        value = value << 8 | std::uint8_t(bytes.at(offset + std::size_t(b)));
    return value;
}

std::string fileBytes(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// A KTX1 file as its header and key/value data state it (KTX 1.1 layout, read independently of the writer).
struct Ktx1Header {
    std::uint32_t field[13]; // endianness .. bytesOfKeyValueData
    std::map<std::string, std::string> keyValues;
    std::vector<std::uint32_t> imageSizes; // per level: bytes of one face
    std::vector<std::size_t> imageOffsets; // per level: first byte of face 0
    std::size_t end = 0;
};
Ktx1Header parseKtx1(const std::string& bytes) {
    Ktx1Header h;
    const unsigned char identifier[12] = {0xAB, 0x4B, 0x54, 0x58, 0x20, 0x31,
                                          0x31, 0xBB, 0x0D, 0x0A, 0x1A, 0x0A};
    EXPECT_EQ(std::memcmp(bytes.data(), identifier, 12), 0);
    for (int i = 0; i < 13; ++i)
        h.field[i] = u32At(bytes, 12 + 4 * std::size_t(i));
    std::size_t at = 64;
    const std::size_t keyValueEnd = at + h.field[12];
    while (at < keyValueEnd) {
        const std::uint32_t size = u32At(bytes, at);
        const std::string pair = bytes.substr(at + 4, size);
        const std::size_t nul = pair.find('\0');
        h.keyValues[pair.substr(0, nul)] = pair.substr(nul + 1);
        at += 4 + size + (3 - (size + 3) % 4);
    }
    for (std::uint32_t m = 0; m < h.field[11]; ++m) {
        h.imageSizes.push_back(u32At(bytes, at));
        h.imageOffsets.push_back(at + 4);
        at += 4 + 6 * std::size_t(h.imageSizes.back());
    }
    h.end = at;
    return h;
}

// An unsigned small float of a 5-bit exponent (bias 15) and `mantissaBits` (OpenGL ES 3.0, 2.1.3, 2.1.4).
double smallFloat(std::uint32_t code, int mantissaBits) {
    const std::uint32_t exponent = code >> mantissaBits, mantissa = code & ((1u << mantissaBits) - 1u);
    const double fraction = double(mantissa) / double(1u << mantissaBits);
    return exponent == 0 ? std::ldexp(fraction, -14) : std::ldexp(1.0 + fraction, int(exponent) - 15);
}

std::vector<double> numbersIn(const std::string& text) {
    std::vector<double> numbers;
    std::string cleaned;
    for (char c : text.substr(0, std::string::npos))
        cleaned.push_back(c == '(' || c == ')' || c == ',' || c == ';' ? ' ' : c);
    std::istringstream lines(cleaned);
    std::string line;
    while (std::getline(lines, line)) {
        std::istringstream words(line.substr(0, line.find("//")));
        double value;
        while (words >> value)
            numbers.push_back(value);
    }
    return numbers;
}

} // namespace

TEST(Ktx1Bytes, HeaderKeyValuesAndPackedTexels) {
    ibl::Ktx1Cube cube;
    for (int size : {4, 2}) {
        std::vector<ibl::ImageRGBA> faces(6, ibl::ImageRGBA(size, size));
        for (ibl::ImageRGBA& face : faces)
            for (glm::vec4& texel : face.pixels)
                texel = {1.0f, 2.0f, 0.5f, 7.0f};
        cube.levels.push_back(faces);
    }
    cube.keyValues["sh"] = "abc";
    const std::string bytes = ibl::encodeKtx1R11G11B10fCube(cube);
    const Ktx1Header h = parseKtx1(bytes);
    EXPECT_EQ(h.field[0], 0x04030201u); // endianness as written
    EXPECT_EQ(h.field[1], 0x8C3Au);     // glType: GL_R11F_G11F_B10F, which Filament's Ktx1Reader maps
    EXPECT_EQ(h.field[2], 4u);          // glTypeSize
    EXPECT_EQ(h.field[3], 0x1907u);     // glFormat GL_RGB
    EXPECT_EQ(h.field[4], 0x8C3Au);     // glInternalFormat
    EXPECT_EQ(h.field[5], 0x1907u);     // glBaseInternalFormat
    EXPECT_EQ(h.field[6], 4u);
    EXPECT_EQ(h.field[7], 4u);
    EXPECT_EQ(h.field[8], 0u);   // pixelDepth
    EXPECT_EQ(h.field[9], 0u);   // numberOfArrayElements
    EXPECT_EQ(h.field[10], 6u);  // numberOfFaces
    EXPECT_EQ(h.field[11], 2u);  // numberOfMipmapLevels
    EXPECT_EQ(h.field[12], 12u); // 4 + "sh\0abc" + 2 bytes of padding
    EXPECT_EQ(h.keyValues.at("sh"), "abc");
    ASSERT_EQ(h.imageSizes.size(), 2u);
    EXPECT_EQ(h.imageSizes[0], 4u * 4u * 4u); // a non-array cube's imageSize is one face's bytes
    EXPECT_EQ(h.imageSizes[1], 2u * 2u * 4u);
    EXPECT_EQ(h.end, bytes.size());
    // 1 = 2^0: exponent 15, mantissa 0 -> 15 << 6; 2 -> 16 << 6; 0.5 in the 10-bit blue -> 14 << 5.
    const std::uint32_t expected = (15u << 6) | (16u << 6) << 11 | (14u << 5) << 22;
    for (std::size_t m = 0; m < 2; ++m)
        for (std::size_t f = 0; f < 6; ++f)
            EXPECT_EQ(u32At(bytes, h.imageOffsets[m] + f * h.imageSizes[m]), expected) << m << " " << f;
}

TEST(Ktx1Bytes, RefusesWhatR11G11B10fCannotHold) {
    for (float value : {70000.0f, -0.25f, std::nanf("")}) {
        ibl::Ktx1Cube cube;
        cube.levels.emplace_back(6, ibl::ImageRGBA(2, 2));
        cube.levels[0][3].at(1, 0) = {0.0f, 0.0f, value, 1.0f};
        try {
            ibl::encodeKtx1R11G11B10fCube(cube);
            ADD_FAILURE() << value << " was accepted";
        } catch (const ibl::SettingError& e) {
            EXPECT_EQ(e.setting(), "storage");
            EXPECT_NE(std::string(e.what()).find("level 0 face 3 texel (1, 0)"), std::string::npos)
                << e.what();
        }
    }
}

// Filament reads lod = (N - 1) r (2 - r): level m of the filament profile holds the r that lod maps to m.
TEST(FilamentProfile, LevelRoughnessIsWhatPerceptualRoughnessToLodReads) {
    const ibl::EngineProfile& profile = ibl::engineProfile("filament");
    EXPECT_EQ(profile.smallestFace, 16);
    const int levels = 5;
    EXPECT_EQ(ibl::engineLevelRoughness(profile, 0, levels, 256), 0.0f);
    EXPECT_FLOAT_EQ(ibl::engineLevelRoughness(profile, levels - 1, levels, 256), 1.0f);
    for (int m = 0; m < levels; ++m) {
        const double r = ibl::engineLevelRoughness(profile, m, levels, 256);
        EXPECT_NEAR((levels - 1) * r * (2.0 - r), m, 1e-5) << "level " << m;
    }
    EXPECT_NEAR(ibl::engineLevelRoughness(profile, 2, levels, 256), 1.0 - std::sqrt(0.5), 1e-6);
}

// The park bake's export: NAME_ibl.ktx down to 16 px with the SH as its "sh" key, NAME_skybox.ktx, sh.txt.
TEST(ExportFilament, WritesCmgenDeployFiles) {
    const fs::path bake = ibl::test::makeBakeDir("filament_bake");
    const fs::path out = bake / "deploy" / "park";
    // The 100,000-lux bake's circumsolar sky reaches 150,400 cd/m2 in a channel: 4 brings it within
    // R11G11B10F.
    CliRun r =
        runCli("export-filament " + bake.string() + " -o " + out.string() + " --quality draft --intensity 4");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.out.find("refilter 2 levels 32..16 px"), std::string::npos) << r.out;
    const std::string ibl = fileBytes(out / "park_ibl.ktx");
    const Ktx1Header h = parseKtx1(ibl);
    EXPECT_EQ(h.field[6], 32u);
    EXPECT_EQ(h.field[11], 2u);
    ASSERT_EQ(h.imageSizes.size(), 2u);
    EXPECT_EQ(h.imageSizes[1], 16u * 16u * 4u); // the profile's smallest face
    EXPECT_EQ(h.end, ibl.size());
    const Ktx1Header sky = parseKtx1(fileBytes(out / "park_skybox.ktx"));
    EXPECT_EQ(sky.field[6], 32u);
    EXPECT_EQ(sky.field[11], 1u);
    EXPECT_TRUE(sky.keyValues.empty());
    // The skybox is the bake's level 0 / intensity: the ground face (-Y, far from the sun), within
    // R11G11B10F's rounding (half a step: 2^-7 of the value for R and G, 2^-6 for B).
    ibl::Ktx2Image bakeLevels = ibl::readKtx2(bake / "specular.ktx2");
    ibl::unscaleKtx2Texels(bakeLevels);
    const std::string skyBytes = fileBytes(out / "park_skybox.ktx");
    const ibl::ImageRGBA& ground = bakeLevels.levels[0][3];
    double worst = 0.0;
    for (int y = 0; y < 32; ++y)
        for (int x = 0; x < 32; ++x) {
            const std::uint32_t word =
                u32At(skyBytes, sky.imageOffsets[0] + 3 * sky.imageSizes[0] + 4 * (32 * y + x));
            const double decoded[3] = {smallFloat(word & 0x7FF, 6), smallFloat(word >> 11 & 0x7FF, 6),
                                       smallFloat(word >> 22, 5)};
            for (int c = 0; c < 3; ++c) {
                const double expected = ground.at(x, y)[c] / 4.0;
                worst = std::max(worst, std::abs(decoded[c] - expected) / expected);
                EXPECT_NEAR(decoded[c], expected, expected * (c == 2 ? 1.0 / 64 : 1.0 / 128) + 1e-9)
                    << x << " " << y;
            }
        }
    std::printf("ground face: largest relative difference from level 0 / 4: %.4f\n", worst);
    // The "sh" key holds sh.txt's 27 numbers.
    std::ifstream shFile(out / "sh.txt");
    const std::string shText{std::istreambuf_iterator<char>(shFile), std::istreambuf_iterator<char>()};
    const std::vector<double> fromText = numbersIn(shText), fromKey = numbersIn(h.keyValues.at("sh"));
    ASSERT_EQ(fromText.size(), 27u) << shText;
    ASSERT_EQ(fromKey.size(), 27u) << h.keyValues.at("sh");
    for (std::size_t i = 0; i < 27; ++i)
        EXPECT_NEAR(fromKey[i], fromText[i], 1e-7 * std::abs(fromText[i]) + 1e-12) << i;
    // ... which are the bake's diffuse.json sh.irradianceOverPi / intensity (Filament's pre-scaled SH).
    std::ifstream diffuseFile(bake / "diffuse.json");
    const nlohmann::json overPi = nlohmann::json::parse(diffuseFile).at("sh").at("irradianceOverPi");
    for (std::size_t i = 0; i < 27; ++i) {
        const double expected = overPi.at(i / 3).at(i % 3).get<double>() / 4.0;
        EXPECT_NEAR(fromKey[i], expected, 1e-6 * std::abs(expected) + 1e-9) << i;
    }
    EXPECT_GT(fromKey[0], 0.0); // L00 of a lit scene
    fs::remove_all(bake);
}

// Each refusal is one line naming the setting, and no file or directory is left.
TEST(ExportFilament, RefusesWhatTheProfileCannotHoldAndWritesNothing) {
    const fs::path bake = ibl::test::makeBakeDir("filament_refusals");
    const fs::path out = bake / "deploy";
    CliRun small = runCli("export-filament " + bake.string() + " -o " + out.string() + " --min-face-size 8");
    EXPECT_EQ(small.exitCode, 1);
    EXPECT_EQ(ibl::test::lineCount(small.err), 1) << small.err;
    EXPECT_NE(small.err.find("--min-face-size: 8 is below the filament profile's smallest face, 16"),
              std::string::npos)
        << small.err;
    EXPECT_FALSE(fs::exists(out));

    // Level 0 of 16 px cannot hold two levels down to 16 px.
    const std::string hdri = ibl::test::sampleHdri();
    ASSERT_EQ(
        runCli("specular " + hdri + " --size 16 --quality draft -o " + (bake / "specular.ktx2").string())
            .exitCode,
        0);
    CliRun tiny = runCli("export-filament " + bake.string() + " -o " + out.string());
    EXPECT_EQ(tiny.exitCode, 1);
    EXPECT_EQ(ibl::test::lineCount(tiny.err), 1) << tiny.err;
    EXPECT_NE(tiny.err.find("specular.ktx2: level 0 is 16 px"), std::string::npos) << tiny.err;
    EXPECT_FALSE(fs::exists(out));

    // A million times the HDRI is beyond R11G11B10F's 65,024 at intensity 1 (the KTX2 holds it with a
    // storage scale); the refusal names the intensity that fits, which then exports.
    ASSERT_EQ(runCli("specular " + hdri + " --size 32 --scale 1e6 --quality draft -o " +
                     (bake / "specular.ktx2").string())
                  .exitCode,
              0);
    CliRun bright = runCli("export-filament " + bake.string() + " -o " + out.string() + " --quality draft");
    EXPECT_EQ(bright.exitCode, 1);
    EXPECT_EQ(ibl::test::lineCount(bright.err), 1) << bright.err;
    const std::size_t at = bright.err.find("give at least ");
    ASSERT_NE(at, std::string::npos) << bright.err;
    EXPECT_EQ(bright.err.rfind("iblbake: error: --intensity: 1 leaves level 0's brightest channel at ", 0),
              0u)
        << bright.err;
    EXPECT_FALSE(fs::exists(out));
    const std::string fitting =
        bright.err.substr(at + 14, bright.err.find_first_of(" \n", at + 14) - at - 14);
    EXPECT_EQ(runCli("export-filament " + bake.string() + " -o " + out.string() +
                     " --quality draft --intensity " + fitting)
                  .exitCode,
              0);
    EXPECT_TRUE(fs::exists(out / "deploy_ibl.ktx"));
    fs::remove_all(bake);
}
