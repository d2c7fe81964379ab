// The CLI as a user meets it: exit codes, one-line errors, no partial output, intact existing files.
#include "cli_runner.h"

#include <gtest/gtest.h>

#include <OpenImageIO/imageio.h>

#include <filesystem>
#include <fstream>

namespace fs = std::filesystem;

namespace {

using ibl::test::CliRun;
using ibl::test::entryCount;
using ibl::test::lineCount;
CliRun run(const std::string& args) {
    return ibl::test::runCli(args);
}
fs::path tempDir(const std::string& name) {
    return ibl::test::freshTempDir(name);
}

TEST(Cli, DfgWritesLayoutMetadata) {
    fs::path dir = tempDir("dfg");
    CliRun r = run("dfg --size 16 --samples 64 --backend cpu -o " + (dir / "lut.exr").string());
    ASSERT_EQ(r.exitCode, 0) << r.err;
    auto in = OIIO::ImageInput::open((dir / "lut.exr").string());
    ASSERT_TRUE(in);
    const OIIO::ImageSpec& spec = in->spec();
    EXPECT_EQ(spec.width, 16);
    EXPECT_EQ(spec.nchannels, 3);
    EXPECT_EQ(spec.channelnames, (std::vector<std::string>{"R", "G", "B"}));
    EXPECT_NE(spec.get_string_attribute("iblbake:layout").find("DFG1"), std::string::npos);
    EXPECT_EQ(spec.format, OIIO::TypeDesc::FLOAT);
    // Only the output, no temporary file left beside it.
    EXPECT_EQ(entryCount(dir), 1u);
    fs::remove_all(dir);
}

TEST(Cli, HalfOutput) {
    fs::path dir = tempDir("half");
    ASSERT_EQ(run("dfg --size 8 --samples 16 --half --backend cpu -o " + (dir / "lut.exr").string()).exitCode,
              0);
    auto in = OIIO::ImageInput::open((dir / "lut.exr").string());
    ASSERT_TRUE(in);
    EXPECT_EQ(in->spec().format, OIIO::TypeDesc::HALF);
    fs::remove_all(dir);
}

TEST(Cli, BadOptionIsOneLineAndNonZero) {
    for (std::string args :
         {"dfg --size banana -o x.exr", "dfg --size 0 -o x.exr", "dfg", "dfg --bogus -o x.exr", "frobnicate",
          "dfg --backend quantum -o x.exr", "dfg --half --float -o x.exr"}) {
        CliRun r = run(args);
        EXPECT_NE(r.exitCode, 0) << args;
        EXPECT_EQ(lineCount(r.err), 1) << args << ": " << r.err;
        EXPECT_EQ(r.err.rfind("iblbake: error:", 0), 0u) << r.err;
    }
    EXPECT_FALSE(fs::exists("x.exr"));
}

TEST(Cli, UnwritableOutputIsOneLineNonZeroAndNothingPartial) {
    CliRun r = run("dfg --size 8 --samples 16 --backend cpu -o /nonexistent-dir/lut.exr");
    EXPECT_NE(r.exitCode, 0);
    EXPECT_EQ(lineCount(r.err), 1) << r.err;
    EXPECT_NE(r.err.find("/nonexistent-dir/lut.exr"), std::string::npos) << r.err;

    // A read-only directory (skipped as root, who may write anywhere).
    fs::path dir = tempDir("ro");
    fs::permissions(dir, fs::perms::owner_read | fs::perms::owner_exec);
    if (::geteuid() != 0) {
        CliRun ro = run("dfg --size 8 --samples 16 --backend cpu -o " + (dir / "lut.exr").string());
        EXPECT_NE(ro.exitCode, 0);
        EXPECT_EQ(lineCount(ro.err), 1) << ro.err;
    }
    fs::permissions(dir, fs::perms::owner_all);
    fs::remove_all(dir);
}

TEST(Cli, FailedWriteKeepsExistingFile) {
    // The target exists as a directory: the write fails and the user's data stays as it was.
    fs::path dir = tempDir("keep");
    fs::create_directories(dir / "lut.exr");
    std::ofstream(dir / "lut.exr" / "precious.txt") << "keep me";
    CliRun r = run("dfg --size 8 --samples 16 --backend cpu -o " + (dir / "lut.exr").string());
    EXPECT_NE(r.exitCode, 0);
    EXPECT_EQ(lineCount(r.err), 1) << r.err;
    EXPECT_TRUE(fs::exists(dir / "lut.exr" / "precious.txt"));
    EXPECT_EQ(entryCount(dir), 1u);
    fs::remove_all(dir);
}

TEST(Cli, NoOpenCLDeviceFallsBackToCpuWithOneWarning) {
    fs::path dir = tempDir("fallback");
    // An empty ICD vendor directory hides every OpenCL platform from the ICD loader. (A reference chain:
    // `dfg` alone and production chains up to 256 px run on the CPU backend under auto, dfg_lut.h
    // standaloneDfgBackend, specular.h standaloneSpecularBackend.)
    ::setenv("OCL_ICD_VENDORS", (dir / "no-icds").c_str(), 1);
    CliRun autoRun = run("specular " + ibl::test::kSampleHdri + " --size 8 --quality reference -o " +
                         (dir / "ld.ktx2").string());
    CliRun forced = run("dfg --size 8 --samples 16 --backend opencl -o " + (dir / "forced.exr").string());
    ::unsetenv("OCL_ICD_VENDORS");
    EXPECT_EQ(autoRun.exitCode, 0) << autoRun.err;
    EXPECT_EQ(lineCount(autoRun.err), 1) << autoRun.err;
    EXPECT_NE(autoRun.err.find("iblbake: warning:"), std::string::npos) << autoRun.err;
    EXPECT_NE(autoRun.out.find("cpu (TBB)"), std::string::npos) << autoRun.out;
    // Forcing OpenCL without a device is an error, not a silent fallback.
    EXPECT_NE(forced.exitCode, 0);
    EXPECT_EQ(lineCount(forced.err), 1) << forced.err;
    EXPECT_FALSE(fs::exists(dir / "forced.exr"));
    fs::remove_all(dir);
}

TEST(Cli, DevicesAndTiming) {
    CliRun devices = run("devices");
    EXPECT_EQ(devices.exitCode, 0);
    EXPECT_FALSE(devices.out.empty());
    fs::path dir = tempDir("timing");
    CliRun timed = run("dfg --size 16 --samples 64 --timing -o " + (dir / "lut.exr").string());
    EXPECT_EQ(timed.exitCode, 0) << timed.err;
    EXPECT_NE(timed.out.find("timing: stage"), std::string::npos) << timed.out;
    fs::remove_all(dir);
}

// The front end hands the engine glibc's malloc tunable for transparent huge pages (cli/front_end.cpp:
// a bake's first touches of 20-60 MB took a page fault per 4 KB), keeps the caller's other tunables, and
// leaves a caller's own choice of it alone. The engine here is a script that prints what it was given.
TEST(Cli, FrontEndAsksTheEngineForHugePagesUnlessTheCallerChose) {
    const fs::path dir = tempDir("huge_pages");
    const fs::path engine = dir / "engine.sh";
    {
        std::ofstream script(engine);
        script << "#!/bin/sh\nprintf '%s' \"$GLIBC_TUNABLES\"\n";
    }
    fs::permissions(engine, fs::perms::owner_all);
    const std::pair<const char*, const char*> cases[] = {
        {"env -u GLIBC_TUNABLES", "glibc.malloc.hugetlb=1"},
        {"env GLIBC_TUNABLES=glibc.malloc.check=0", "glibc.malloc.check=0:glibc.malloc.hugetlb=1"},
        {"env GLIBC_TUNABLES=glibc.malloc.hugetlb=0", "glibc.malloc.hugetlb=0"},
    };
    for (const auto& [environment, expected] : cases) {
        const CliRun r = ibl::test::runProgram(
            std::string(environment) + " IBLBAKE_ENGINE=" + engine.string() + " " + IBLBAKE_CLI, "specular");
        EXPECT_EQ(r.exitCode, 0) << environment << ": " << r.err;
        EXPECT_EQ(r.out, expected) << environment;
    }
    fs::remove_all(dir);
}

} // namespace

// A command writes one container per output; a file named for another (a .dds holding KTX2) is refused in one
// line naming the file and the container it would be, before any work, and nothing is written.
TEST(Cli, AnOutputNamedForAnotherContainerIsRefused) {
    const fs::path dir = ibl::test::freshTempDir("cli_extensions");
    const std::string hdri = std::string(IBLBAKE_SOURCE_DIR) + "/data/rooitou_park_1k.hdr";
    const struct {
        std::string args, file, container;
    } cases[] = {
        {"specular " + hdri + " --size 16 --quality draft -o", "chain.exr", "KTX2 (.ktx2) or DDS (.dds)"},
        {"specular " + hdri + " --size 16 --quality draft -o chain.ktx2 --rough-layers", "rough.exr",
         "KTX2 (.ktx2) or DDS (.dds)"},
        {"dfg --size 8 --samples 8 -o", "lut.ktx2", "OpenEXR (.exr)"},
        {"diffuse " + hdri + " --size 16 -o", "d.txt", "JSON (.json)"},
        {"diffuse " + hdri + " --size 16 -o d.json --irradiance-cube", "irr.png",
         "KTX2 (.ktx2) or DDS (.dds)"},
        {"calibrate " + hdri + " --scale 2 -o", "cal.hdr", "OpenEXR (.exr)"},
        {"lightcard " + hdri + " --size 4 -o", "card", "KTX2 (.ktx2)"},
    };
    for (const auto& c : cases) {
        const CliRun r = run(c.args + " " + (dir / c.file).string());
        EXPECT_EQ(r.exitCode, 1) << c.args;
        EXPECT_EQ(lineCount(r.err), 1) << r.err;
        EXPECT_NE(r.err.find(c.file + ": written as " + c.container), std::string::npos) << r.err;
        EXPECT_EQ(entryCount(dir), 0u) << c.args;
    }
    fs::remove_all(dir);
}
