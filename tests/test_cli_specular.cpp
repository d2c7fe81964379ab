// `iblbake specular` end to end: the sample HDRI in, a valid KTX2 chain with its metadata, the EXR
// levels and the preview out; bad input refused with one line and nothing written.
#include "cli_runner.h"
#include "scene_test_support.h"

#include <iblbake/ktx2/ktx2.h>
#include <iblbake/ktx2/storage_scale.h>

#include <mip_mapping.h>

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

namespace fs = std::filesystem;

namespace {

using namespace ibl::test;

TEST(CliSpecular, BakesTheSampleToKtx2ExrAndPreview) {
    fs::path dir = freshTempDir("specular");
    CliRun r = runCli("specular " + kSampleHdri + " --size 32 --quality draft --backend cpu -o " +
                      (dir / "env.ktx2").string() + " --exr " + (dir / "levels").string() + " --preview " +
                      (dir / "preview.png").string());
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.out.find("level  5"), std::string::npos) << r.out;

    ibl::Ktx2Image ktx = ibl::readKtx2(dir / "env.ktx2");
    EXPECT_EQ(ktx.vkFormat, 97u); // VK_FORMAT_R16G16B16A16_SFLOAT
    EXPECT_EQ(ktx.faceCount, 6u);
    EXPECT_EQ(ktx.levelCount, 6u);
    EXPECT_EQ(ktx.pixelWidth, 32u);
    EXPECT_EQ(ktx.keyValues.at("iblbake.roughnessMapping"), "frostbite"); // the name; its meaning beside it
    EXPECT_NE(ktx.keyValues.at("iblbake.roughnessMappingMeaning").find("(m/(L-1))^2"), std::string::npos);
    EXPECT_EQ(ktx.keyValues.at("iblbake.colorSpace"), "lin_rec709");
    EXPECT_EQ(ktx.keyValues.at("iblbake.levelCount"), "6");
    for (const auto& level : ktx.levels)
        for (const auto& face : level)
            for (const glm::vec4& p : face.pixels)
                ASSERT_TRUE(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z));
    for (int m = 0; m < 6; ++m)
        EXPECT_TRUE(fs::exists(dir / "levels" / ("level_" + std::to_string(m) + ".exr"))) << m;
    EXPECT_GT(fs::file_size(dir / "preview.png"), 1000u);
    EXPECT_EQ(entryCount(dir), 3u); // env.ktx2, levels/, preview.png: no temporaries left
    fs::remove_all(dir);
}

TEST(CliSpecular, CalibrationAndSunExtractionAreRecorded) {
    fs::path dir = freshTempDir("specular_calibrated");
    CliRun r = runCli(
        "specular " + kSampleHdri + " --size 64 --quality draft --backend cpu --sun-illuminance 100000 " +
        "--extract-sun --sun-json " + (dir / "sun.json").string() + " -o " + (dir / "env.ktx2").string());
    ASSERT_EQ(r.exitCode, 0) << r.err;
    ibl::Ktx2Image ktx = ibl::readKtx2(dir / "env.ktx2");
    EXPECT_EQ(ktx.keyValues.at("iblbake.units"), "cd/m2");
    EXPECT_EQ(ktx.keyValues.at("iblbake.calibration.source"), "sun-illuminance");
    EXPECT_GT(std::stod(ktx.keyValues.at("iblbake.calibration.factor")), 1000.0);
    EXPECT_NE(ktx.keyValues.at("iblbake.sun").find("extracted"), std::string::npos);
    std::ifstream sun(dir / "sun.json");
    std::string text(std::istreambuf_iterator<char>(sun), {});
    EXPECT_NE(text.find("\"illuminanceLux\": 99999.99"), std::string::npos) << text;
    // A calibrated sun (~1e9 cd/m2) does not fit half floats as it is: level 0 keeps it with a storage scale
    // (docs/conventions.md "Float storage and the storage scale"), which the readers divide out.
    EXPECT_EQ(ktx.keyValues.at("iblbake.sunInLevel0"), "true");
    EXPECT_LT(ibl::ktx2StorageScale(ktx), 1.0);
    ibl::unscaleKtx2Texels(ktx);
    // Clamped to half floats on request, level 0 is the residual, as every level.
    r = runCli("specular " + kSampleHdri +
               " --size 64 --quality draft --backend cpu --sun-illuminance 100000 " +
               "--extract-sun --sun-json " + (dir / "sun16.json").string() + " --clamp-to-format -o " +
               (dir / "clamped.ktx2").string());
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const ibl::Ktx2Image residual = ibl::readKtx2(dir / "clamped.ktx2");
    EXPECT_EQ(residual.keyValues.count("iblbake.sunInLevel0"), 0u);
    // In 32-bit floats level 0 keeps it (the unconvolved source): the sun's pixels, far above the residual.
    r = runCli("specular " + kSampleHdri +
               " --size 64 --quality draft --backend cpu --sun-illuminance 100000 " +
               "--extract-sun --sun-json " + (dir / "sun32.json").string() + " --format rgba32f -o " +
               (dir / "env32.ktx2").string());
    ASSERT_EQ(r.exitCode, 0) << r.err;
    ibl::Ktx2Image full = ibl::readKtx2(dir / "env32.ktx2");
    EXPECT_EQ(full.keyValues.at("iblbake.sunInLevel0"), "true");
    float peakFull = 0.0f, peakResidual = 0.0f;
    for (int f = 0; f < 6; ++f)
        for (std::size_t i = 0; i < full.levels[0][f].pixels.size(); ++i) {
            peakFull = std::max(peakFull, full.levels[0][f].pixels[i].g);
            peakResidual = std::max(peakResidual, residual.levels[0][f].pixels[i].g);
        }
    EXPECT_GT(peakFull, 1000.0f * peakResidual);
    for (std::size_t i = 0; i < full.levels[1][0].pixels.size();
         ++i) // level 1 on: the residual's (half, scaled)
        ASSERT_NEAR(full.levels[1][0].pixels[i].g, ktx.levels[1][0].pixels[i].g,
                    1e-3f * std::abs(full.levels[1][0].pixels[i].g) + 1e-6f);
    // Two calibration sources: one line, non-zero, nothing written.
    CliRun two = runCli("specular " + kSampleHdri + " --size 8 --ev100 12 --illuminance 5 -o " +
                        (dir / "two.ktx2").string());
    EXPECT_NE(two.exitCode, 0);
    EXPECT_EQ(lineCount(two.err), 1) << two.err;
    EXPECT_FALSE(fs::exists(dir / "two.ktx2"));
    fs::remove_all(dir);
}

TEST(CliSpecular, EveryFormatIsWritten) {
    fs::path dir = freshTempDir("formats");
    const std::pair<const char*, unsigned> formats[] = {
        {"rgba16f", 97}, {"rgba32f", 109}, {"b10g11r11", 122}, {"e5b9g9r9", 123}};
    for (auto [name, vk] : formats) {
        fs::path out = dir / (std::string(name) + ".ktx2");
        CliRun r = runCli("specular " + kSampleHdri + " --size 8 --quality draft --backend cpu --format " +
                          name + " -o " + out.string());
        ASSERT_EQ(r.exitCode, 0) << name << ": " << r.err;
        EXPECT_EQ(ibl::readKtx2(out).vkFormat, vk);
    }
    fs::remove_all(dir);
}

// --rough-layers: the chain's rough layers beside it, as a scene bake writes them, readable by the runtime
// loader and equal to the library's bake within the format's rounding; the chain's file is the same bytes
// as without the option.
TEST(CliSpecular, RoughLayersBesideTheChain) {
    fs::path dir = freshTempDir("specular_rough");
    const std::string common = "specular " + kSampleHdri + " --size 64 --quality draft --backend cpu ";
    CliRun with = runCli(common + "-o " + (dir / "a.ktx2").string() + " --rough-layers " +
                         (dir / "a_rough.ktx2").string());
    ASSERT_EQ(with.exitCode, 0) << with.err;
    EXPECT_NE(with.out.find("12 rough layers of 32 px"), std::string::npos) << with.out;
    CliRun without = runCli(common + "-o " + (dir / "b.ktx2").string());
    ASSERT_EQ(without.exitCode, 0) << without.err;
    EXPECT_EQ(readBytes(dir / "a.ktx2"), readBytes(dir / "b.ktx2"));
    ibl::Ktx2Image rough = ibl::readKtx2(dir / "a_rough.ktx2");
    EXPECT_EQ(rough.faceCount, 6u);
    EXPECT_EQ(rough.layerCount, 12u);
    EXPECT_EQ(rough.pixelWidth, 32u);
    EXPECT_EQ(rough.keyValues.at("iblbake.product"), "specular-rough-layers");
    EXPECT_EQ(rough.keyValues.at("iblbake.roughLayerRoughness"), ibl::roughLayerRoughnessText());
    EXPECT_EQ(rough.keyValues.at("iblbake.source"), fs::path(kSampleHdri).filename().string());
    fs::remove_all(dir);
}

// --profile three: the chain three.js r187 samples as is (docs/engines.md "three.js"): down to 8-px faces and
// never fewer than 6 levels, level m of N holding the r that three's roughnessToMip, (N - 1) r (2 - r), maps
// to m, named by the file (iblbake.roughnessMapping filament-lod, iblbake.levelRoughness) and its --exr
// levels.
TEST(CliSpecular, ThreeProfileHoldsWhatThreeReadsAtEveryLevel) {
    fs::path dir = freshTempDir("specular_three");
    for (const auto& [size, levels] : {std::pair{256, 6}, std::pair{512, 7}, std::pair{64, 6}}) {
        const fs::path file = dir / ("three_" + std::to_string(size) + ".ktx2");
        const fs::path exr = dir / ("levels_" + std::to_string(size));
        CliRun run = runCli("specular " + kSampleHdri + " --size " + std::to_string(size) +
                            " --quality draft --backend cpu --profile three -o " + file.string() + " --exr " +
                            exr.string());
        ASSERT_EQ(run.exitCode, 0) << run.err;
        const ibl::Ktx2Image ktx = ibl::readKtx2(file);
        EXPECT_EQ(ktx.levelCount, std::uint32_t(levels)) << size;
        EXPECT_EQ(ktx.keyValues.at("iblbake.profile"), "three");
        EXPECT_EQ(ktx.keyValues.at("iblbake.roughnessMapping"), "filament-lod");
        std::istringstream list(ktx.keyValues.at("iblbake.levelRoughness"));
        std::vector<double> roughness;
        for (std::string value; std::getline(list, value, ',');)
            roughness.push_back(std::stod(value));
        ASSERT_EQ(roughness.size(), std::size_t(levels)) << ktx.keyValues.at("iblbake.levelRoughness");
        for (int m = 0; m < levels; ++m) {
            const double r = roughness[std::size_t(m)];
            EXPECT_NEAR((levels - 1) * r * (2.0 - r), m, 1e-5) << size << " level " << m;
            // The --exr levels say the same.
            auto in = OIIO::ImageInput::open((exr / ("level_" + std::to_string(m) + ".exr")).string());
            ASSERT_TRUE(in) << size << " level " << m;
            EXPECT_EQ(in->spec().get_string_attribute("iblbake:roughnessMapping"), "filament-lod");
            EXPECT_NEAR(std::stod(in->spec().get_string_attribute("iblbake:levelRoughness")), r, 1e-6);
        }
    }
    fs::remove_all(dir);
}

TEST(CliSpecular, BadInputIsOneLineNonZeroAndWritesNothing) {
    fs::path dir = freshTempDir("specular_bad");
    std::ofstream(dir / "notes.txt") << "this is not an image\n";
    std::ofstream(dir / "keep.ktx2") << "precious";
    const std::string out = " -o " + (dir / "keep.ktx2").string();
    const std::pair<std::string, std::string> cases[] = {
        {"specular " + (dir / "missing.hdr").string() + out, "missing.hdr"},
        {"specular " + (dir / "notes.txt").string() + out, "notes.txt"},
        {"specular " + kSampleHdri + " --size 100" + out, "--size"},
        {"specular " + kSampleHdri + " --format astc" + out, "--format"},
        {"specular " + kSampleHdri + " --quality ultra" + out, "--quality"},
        {"specular " + kSampleHdri + " --layout hexagon" + out, "--layout: 'hexagon'"},
        {"specular " + kSampleHdri + " --size 8 -o /nonexistent-dir/env.ktx2", "/nonexistent-dir/env.ktx2"},
        {"specular " + kSampleHdri + " --size 64 --profile three --levels 3" + out, "--levels"},
        {"specular " + kSampleHdri + " --size 8" + out + " --rough-layers /nonexistent-dir/rough.ktx2",
         "/nonexistent-dir/rough.ktx2"},
    };
    for (const auto& [args, named] : cases) {
        CliRun r = runCli(args);
        EXPECT_NE(r.exitCode, 0) << args;
        EXPECT_EQ(lineCount(r.err), 1) << args << ": " << r.err;
        EXPECT_NE(r.err.find(named), std::string::npos) << args << ": " << r.err;
    }
    std::ifstream kept(dir / "keep.ktx2");
    EXPECT_EQ(std::string(std::istreambuf_iterator<char>(kept), {}), "precious");
    EXPECT_EQ(entryCount(dir), 2u);
    fs::remove_all(dir);
}

// The standalone commands keep program binaries for the user running them (ocl::userProgramBinaryDirectory,
// docs/conventions.md "Kernels, backends and kernel binaries"): the first bake builds its programs and stores
// them, a second loads them and builds none (the same bytes), $XDG_CACHE_HOME moves them, and an empty
// $IBLBAKE_KERNEL_CACHE keeps none.
TEST(CliSpecular, KeepsKernelBinariesForTheUser) {
    const fs::path dir = freshTempDir("specular_kernels");
    const std::string bake =
        "specular " + kSampleHdri + " --size 8 --quality draft --backend opencl --timing -o ";
    auto programs = [](const CliRun& r) {
        const std::size_t at = r.out.find("timing: programs ");
        EXPECT_NE(at, std::string::npos) << r.out;
        return at == std::string::npos ? std::string() : r.out.substr(at, r.out.find('\n', at) - at);
    };
    auto binaries = [](const fs::path& directory) {
        std::size_t count = 0;
        if (fs::is_directory(directory))
            for (const fs::directory_entry& e : fs::directory_iterator(directory))
                count += e.path().extension() == ".clbin";
        return count;
    };
    // PoCL keeps its own cache under the same variables: one directory for it in every run.
    const std::string pocl = " POCL_CACHE_DIR=" + (dir / "pocl").string() + " ";
    const std::string home =
        "env -u IBLBAKE_KERNEL_CACHE -u XDG_CACHE_HOME" + pocl + "HOME=" + (dir / "home").string() + " ";
    const CliRun cold = runProgram(home + IBLBAKE_CLI, bake + (dir / "cold.ktx2").string());
    ASSERT_EQ(cold.exitCode, 0) << cold.err;
    EXPECT_EQ(programs(cold).find("programs 0 built"), std::string::npos) << programs(cold);
    const fs::path kernels = dir / "home" / ".cache" / "iblbake" / "kernels";
    EXPECT_GE(binaries(kernels), 1u);
    const CliRun warm = runProgram(home + IBLBAKE_CLI, bake + (dir / "warm.ktx2").string());
    ASSERT_EQ(warm.exitCode, 0) << warm.err;
    EXPECT_NE(programs(warm).find("programs 0 built from source"), std::string::npos) << programs(warm);
    EXPECT_EQ(readBytes(dir / "cold.ktx2"), readBytes(dir / "warm.ktx2"));

    const CliRun xdg =
        runProgram("env -u IBLBAKE_KERNEL_CACHE" + pocl + "XDG_CACHE_HOME=" + (dir / "xdg").string() +
                       " HOME=" + (dir / "home").string() + " " IBLBAKE_CLI,
                   bake + (dir / "xdg.ktx2").string());
    ASSERT_EQ(xdg.exitCode, 0) << xdg.err;
    EXPECT_GE(binaries(dir / "xdg" / "iblbake" / "kernels"), 1u);

    const CliRun off = runProgram("env" + pocl + "IBLBAKE_KERNEL_CACHE= HOME=" + (dir / "nowhere").string() +
                                      " " IBLBAKE_CLI,
                                  bake + (dir / "off.ktx2").string());
    ASSERT_EQ(off.exitCode, 0) << off.err;
    EXPECT_NE(programs(off).find(", 0 loaded from binaries"), std::string::npos) << programs(off);
    EXPECT_FALSE(fs::exists(dir / "nowhere" / ".cache" / "iblbake"));
    fs::remove_all(dir);
}

} // namespace
