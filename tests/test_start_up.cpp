// Start-up without OpenImageIO (issue 18): the programs link no OpenImageIO, and only an input that is
// neither OpenEXR nor Radiance loads it (the module, baker/src/io/oiio_module.h). The dynamic loader's own
// trace (LD_DEBUG=files) lists every shared object a process initialises, dlopen'ed ones included.
#include "cli_runner.h"

#include <iblbake/baker/dfg_lut.h>
#include <iblbake/baker/exr_output.h>
#include <iblbake/baker/preview.h>
#include <iblbake/baker/specular.h>
#include <iblbake/opencl/executor.h>

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <fstream>

namespace fs = std::filesystem;

namespace {

using namespace ibl::test;

struct Traced {
    ibl::test::CliRun run;
    bool initialisedOiio = false;
};

Traced traced(const std::string& args) {
    Traced t;
    t.run = runProgram("env LD_DEBUG=files " IBLBAKE_CLI, args);
    // The trace names each object as it initialises it; without it the check would pass vacuously.
    EXPECT_NE(t.run.err.find("calling init:"), std::string::npos) << t.run.err.substr(0, 400);
    t.initialisedOiio = t.run.err.find("libOpenImageIO") != std::string::npos;
    return t;
}

TEST(StartUp, OpenExrAndRadianceWorkLoadNoOpenImageIO) {
    const fs::path dir = fs::temp_directory_path() / ("iblbake_start_up_" + std::to_string(::getpid()));
    fs::create_directories(dir);
    const std::string bake = " --size 8 --quality draft --backend cpu -o ";
    ibl::ImageRGBA sky(64, 32);
    for (std::size_t i = 0; i < sky.pixels.size(); ++i)
        sky.pixels[i] = glm::vec4(0.5f + float(i % 64) / 64.0f, 0.7f, 0.9f, 1.0f);
    ibl::ExrOutputOptions exr;
    exr.envmap = ibl::ExrEnvmap::LatLong;
    ibl::writeExr(dir / "sky.exr", sky, exr);
    for (const std::string& args :
         {std::string("--version"),
          "dfg --size 8 --samples 16 --backend cpu -o " + (dir / "dfg.exr").string(),
          "specular " + kSampleHdri + bake + (dir / "hdr.ktx2").string(),
          "specular " + (dir / "sky.exr").string() + bake + (dir / "exr.ktx2").string()}) {
        const Traced t = traced(args);
        EXPECT_EQ(t.run.exitCode, 0) << args;
        EXPECT_FALSE(t.initialisedOiio) << args;
    }
    fs::remove_all(dir);
}

// `iblbake dfg` with --backend auto runs on the CPU backend (dfg_lut.h standaloneDfgBackend): the OpenCL
// driver (PoCL here, which the ICD loader dlopens on the platform query) is never initialised; asked for
// OpenCL, it is.
TEST(StartUp, StandaloneDfgLoadsNoOpenClDriverUnlessAsked) {
    const fs::path dir = fs::temp_directory_path() / ("iblbake_start_up_dfg_" + std::to_string(::getpid()));
    fs::create_directories(dir);
    const std::string lut = "dfg --size 8 --samples 16 -o " + (dir / "dfg.exr").string();
    const Traced automatic = traced(lut);
    EXPECT_EQ(automatic.run.exitCode, 0) << automatic.run.err.substr(0, 400);
    EXPECT_EQ(automatic.run.err.find("libpocl"), std::string::npos);
    EXPECT_NE(automatic.run.out.find("cpu (TBB)"), std::string::npos) << automatic.run.out;
    const Traced opencl = traced(lut + " --backend opencl");
    EXPECT_EQ(opencl.run.exitCode, 0) << opencl.run.err.substr(0, 400);
    EXPECT_NE(opencl.run.err.find("libpocl"), std::string::npos);
    EXPECT_EQ(ibl::standaloneDfgBackend(ibl::Backend::Auto, true), ibl::Backend::Auto) << "a named device";
    EXPECT_EQ(ibl::standaloneDfgBackend(ibl::Backend::OpenCL, false), ibl::Backend::OpenCL);
    fs::remove_all(dir);
}

// `iblbake specular` of a production chain up to 256 px runs on the CPU backend under auto
// (specular.h standaloneSpecularBackend); a larger or a reference chain, a named device or an explicit
// backend keeps what was asked.
TEST(StartUp, SmallStandaloneChainLoadsNoOpenClDriverUnlessAsked) {
    const fs::path dir = fs::temp_directory_path() / ("iblbake_start_up_ld_" + std::to_string(::getpid()));
    fs::create_directories(dir);
    const std::string chain =
        "specular " + kSampleHdri + " --size 8 --quality draft -o " + (dir / "ld.ktx2").string();
    const Traced automatic = traced(chain);
    EXPECT_EQ(automatic.run.exitCode, 0) << automatic.run.err.substr(0, 400);
    EXPECT_EQ(automatic.run.err.find("libpocl"), std::string::npos);
    const Traced opencl = traced(chain + " --backend opencl");
    EXPECT_EQ(opencl.run.exitCode, 0) << opencl.run.err.substr(0, 400);
    EXPECT_NE(opencl.run.err.find("libpocl"), std::string::npos);
    using ibl::Backend;
    const ibl::SpecularSettings production, reference{.quality = ibl::Quality::Reference},
        manySamples{.samples = 1024};
    EXPECT_EQ(ibl::standaloneSpecularBackend(Backend::Auto, false, production, 256), Backend::Cpu);
    EXPECT_EQ(ibl::standaloneSpecularBackend(Backend::Auto, false, production, 512), Backend::Auto);
    EXPECT_EQ(ibl::standaloneSpecularBackend(Backend::Auto, false, reference, 64), Backend::Auto);
    EXPECT_EQ(ibl::standaloneSpecularBackend(Backend::Auto, false, manySamples, 64), Backend::Auto);
    EXPECT_EQ(ibl::standaloneSpecularBackend(Backend::Auto, true, production, 64), Backend::Auto)
        << "a named device";
    EXPECT_EQ(ibl::standaloneSpecularBackend(Backend::OpenCL, false, production, 64), Backend::OpenCL);
    fs::remove_all(dir);
}

// What `auto` runs for a job (executor.h jobBackend, issue 46): the CPU backend where every OpenCL device is
// a CPU, OpenCL where a GPU is found or a device is named; an explicit backend is kept. A scene bake under
// auto on this machine runs on the CPU backend when its devices are CPUs, and on OpenCL when asked.
TEST(StartUp, AutoRunsTheCpuLanesWhereEveryOpenClDeviceIsACpu) {
    using ibl::Backend;
    ibl::ocl::DeviceInfo cpu, gpu;
    cpu.deviceType = "CPU";
    gpu.deviceType = "GPU";
    EXPECT_EQ(ibl::jobBackend(Backend::Auto, false, {cpu}), Backend::Cpu);
    EXPECT_EQ(ibl::jobBackend(Backend::Auto, false, {cpu, gpu}), Backend::Auto) << "a GPU is preferred";
    EXPECT_EQ(ibl::jobBackend(Backend::Auto, true, {cpu}), Backend::Auto) << "a named device";
    EXPECT_EQ(ibl::jobBackend(Backend::Auto, false, {}), Backend::Auto) << "no device: the warned fallback";
    EXPECT_EQ(ibl::jobBackend(Backend::OpenCL, false, {cpu}), Backend::OpenCL);
    EXPECT_EQ(ibl::jobBackend(Backend::Cpu, false, {gpu}), Backend::Cpu);

    const fs::path dir = ibl::test::freshTempDir("start_up_auto_scene");
    const nlohmann::json scene = {
        {"environment", {{"file", kSampleHdri}}},
        {"outputs", {{"directory", (dir / "out").string()}, {"quality", "draft"}, {"faceSize", 16}}}};
    std::ofstream(dir / "scene.json") << scene.dump();
    const auto backendOf = [&](const std::string& flags) {
        const CliRun r = runCli("bake " + (dir / "scene.json").string() + " --json --force" + flags);
        EXPECT_EQ(r.exitCode, 0) << r.err;
        const std::string done = r.out.substr(r.out.rfind("{\"event\":\"done\""));
        return nlohmann::json::parse(done)["summary"]["backend"].get<std::string>();
    };
    const std::vector<ibl::ocl::DeviceInfo> devices = ibl::ocl::listDevices();
    if (devices.empty()) GTEST_SKIP() << "no OpenCL device";
    EXPECT_EQ(backendOf(""),
              ibl::jobBackend(Backend::Auto, false, devices) == Backend::Cpu ? "cpu" : "opencl");
    EXPECT_EQ(backendOf(" --backend opencl"), "opencl");
    fs::remove_all(dir);
}

TEST(StartUp, OtherFormatsLoadTheOpenImageIOModule) {
    const fs::path dir = fs::temp_directory_path() / ("iblbake_start_up_png_" + std::to_string(::getpid()));
    fs::create_directories(dir);
    const int width = 64, height = 32;
    ibl::writeSrgb8Png(dir / "sky.png", width, height, std::vector<unsigned char>(width * height * 3, 128));
    const Traced t = traced("specular " + (dir / "sky.png").string() +
                            " --size 8 --quality draft --backend cpu -o " + (dir / "png.ktx2").string());
    EXPECT_EQ(t.run.exitCode, 0) << t.run.err.substr(t.run.err.size() > 400 ? t.run.err.size() - 400 : 0);
    EXPECT_TRUE(t.initialisedOiio);
    EXPECT_TRUE(fs::exists(dir / "png.ktx2"));
    fs::remove_all(dir);
}

} // namespace
