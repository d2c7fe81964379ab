// Program binaries kept on disk (docs/conventions.md "Kernels, backends and kernel binaries"): a fresh
// context with a warm directory builds no program from source and bakes the same bytes; a damaged binary is
// rebuilt from source, never trusted.
#include "cli_runner.h"
#include "scene_test_support.h"

#include <iblbake/baker/dfg_lut.h>
#include <iblbake/opencl/executor.h>

#include <gtest/gtest.h>

#include <cstring>
#include <fstream>
#include <iostream>

namespace fs = std::filesystem;

namespace {

// A context of its own (no programs built yet), reading and writing binaries in `directory`.
ibl::Executor freshExecutor(const fs::path& directory) {
    ibl::Executor executor = ibl::Executor::create(ibl::Backend::OpenCL, "", std::cerr);
    executor.cl().useProgramBinaries(directory);
    return executor;
}

ibl::ImageRGBA bakeSmallLut(const ibl::Executor& executor) {
    ibl::DfgSettings settings;
    settings.size = 16;
    settings.sampleCount = 64;
    return ibl::bakeDfgLut(settings, executor);
}

bool sameBytes(const ibl::ImageRGBA& a, const ibl::ImageRGBA& b) {
    return a.pixels.size() == b.pixels.size() &&
           std::memcmp(a.pixels.data(), b.pixels.data(), a.pixels.size() * sizeof a.pixels[0]) == 0;
}

std::vector<fs::path> binaries(const fs::path& directory) {
    std::vector<fs::path> out;
    for (const auto& e : fs::directory_iterator(directory))
        if (e.path().extension() == ".clbin") out.push_back(e.path());
    return out;
}

class ProgramBinaries : public ::testing::Test {
  protected:
    void SetUp() override {
        if (ibl::ocl::listDevices().empty()) GTEST_SKIP() << "no OpenCL device";
        dir = ibl::test::freshTempDir(::testing::UnitTest::GetInstance()->current_test_info()->name());
        ibl::Executor cold = freshExecutor(dir / "kernels");
        reference = bakeSmallLut(cold);
        EXPECT_EQ(cold.cl().programBuilds().fromBinary, 0);
        EXPECT_GE(cold.cl().programBuilds().fromSource, 1);
        EXPECT_FALSE(fs::exists(dir / "kernels")) << "binaries written before the command's outputs were";
        cold.cl().storeProgramBinaries();
        ASSERT_EQ(binaries(dir / "kernels").size(), std::size_t(cold.cl().programBuilds().fromSource));
    }
    void TearDown() override {
        if (!dir.empty()) fs::remove_all(dir);
    }
    fs::path dir;
    ibl::ImageRGBA reference;
};

TEST_F(ProgramBinaries, AWarmDirectoryBuildsNoProgramFromSource) {
    ibl::Executor warm = freshExecutor(dir / "kernels");
    EXPECT_TRUE(sameBytes(bakeSmallLut(warm), reference));
    EXPECT_EQ(warm.cl().programBuilds().fromSource, 0);
    EXPECT_GE(warm.cl().programBuilds().fromBinary, 1);
}

TEST_F(ProgramBinaries, DamagedBinariesAreRebuiltFromSourceAndReplaced) {
    // program_binaries.cpp's header: the magic and the key, then the payload's hash.
    constexpr std::size_t kMagicAndKeyBytes = 8 + 32;
    const fs::path file = binaries(dir / "kernels").front();
    std::string bytes = ibl::test::readBytes(file);
    std::string flippedPayload = bytes, foreignKey = bytes;
    flippedPayload[bytes.size() - 9] ^= 0x20;
    foreignKey[9] = foreignKey[9] == '0' ? '1' : '0'; // the header's key (after the 8-byte magic)
    for (const std::string& damaged : {bytes.substr(0, bytes.size() / 2), flippedPayload, foreignKey,
                                       std::string("not a program binary")}) {
        ibl::test::writeText(file, damaged);
        ibl::Executor rebuilt = freshExecutor(dir / "kernels");
        EXPECT_TRUE(sameBytes(bakeSmallLut(rebuilt), reference));
        EXPECT_GE(rebuilt.cl().programBuilds().fromSource, 1);
        rebuilt.cl().storeProgramBinaries(); // the rebuilt binary replaces the damaged file
        // Same magic and key as the first binary; not the same size: PoCL's payload carries the kernels it
        // has specialised so far, which depends on what its cache held when the program was built.
        const std::string replaced = ibl::test::readBytes(file);
        EXPECT_NE(replaced, damaged);
        EXPECT_EQ(replaced.substr(0, kMagicAndKeyBytes), bytes.substr(0, kMagicAndKeyBytes));
        ibl::Executor warm = freshExecutor(dir / "kernels");
        bakeSmallLut(warm);
        EXPECT_EQ(warm.cl().programBuilds().fromSource, 0);
    }
}

} // namespace
