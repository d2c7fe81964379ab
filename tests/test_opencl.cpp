// The OpenCL host layer: diagnostics that name the program, device, options and carry the build log.
#include <iblbake/core/error.h>
#include <iblbake/opencl/executor.h>
#include <iblbake/opencl/opencl_context.h>

#include <gtest/gtest.h>

#include <sstream>

namespace {

std::shared_ptr<ibl::ocl::Context> contextOrSkip() {
    if (ibl::ocl::listDevices().empty()) return nullptr;
    return ibl::ocl::Context::create();
}

TEST(OpenCL, BrokenProgramErrorCarriesBuildLog) {
    auto cl = contextOrSkip();
    if (!cl) GTEST_SKIP() << "no OpenCL device";
    const std::string source = "__kernel void broken(__global float* out) { out[0] = undeclaredThing; }\n";
    try {
        cl->buildProgram("broken.cl", source, "-DMARKER_OPTION=1");
        FAIL() << "a broken program built";
    } catch (const ibl::Error& e) {
        std::string message = e.what();
        EXPECT_NE(message.find("broken.cl"), std::string::npos) << message;
        EXPECT_NE(message.find("-DMARKER_OPTION=1"), std::string::npos) << message;
        EXPECT_NE(message.find(cl->device().deviceName), std::string::npos) << message;
        EXPECT_NE(message.find("CL_BUILD_PROGRAM_FAILURE"), std::string::npos) << message;
        EXPECT_NE(message.find("undeclaredThing"), std::string::npos) << "no build log in: " << message;
    }
}

TEST(OpenCL, EmbeddedSourcesResolveIncludesWithLineMarkers) {
    std::string source = ibl::ocl::assembleProgramSource("dfg.cl");
    EXPECT_NE(source.find("#line 1 \"kernels/portable.h\""), std::string::npos);
    EXPECT_NE(source.find("#line 1 \"kernels/dfg.h\""), std::string::npos);
    EXPECT_NE(source.find("__kernel void dfgLut"), std::string::npos);
    // Each header once, however often it is included.
    std::size_t first = source.find("#line 1 \"kernels/portable.h\"");
    EXPECT_EQ(source.find("#line 1 \"kernels/portable.h\"", first + 1), std::string::npos);
    EXPECT_THROW(ibl::ocl::assembleProgramSource("no_such_kernel.cl"), ibl::Error);
}

TEST(OpenCL, ErrorNamesAreSymbolic) {
    EXPECT_STREQ(ibl::ocl::errorName(CL_OUT_OF_RESOURCES), "CL_OUT_OF_RESOURCES");
    EXPECT_STREQ(ibl::ocl::errorName(CL_INVALID_KERNEL_NAME), "CL_INVALID_KERNEL_NAME");
    EXPECT_STREQ(ibl::ocl::errorName(-12345), "CL_UNKNOWN_ERROR");
}

TEST(OpenCL, ProgramsAreCachedPerProcessAndTimed) {
    auto cl = contextOrSkip();
    if (!cl) GTEST_SKIP() << "no OpenCL device";
    cl::Program& a = cl->program("dfg.cl");
    cl::Program& b = cl->program("dfg.cl");
    EXPECT_EQ(&a, &b);
    EXPECT_THROW(cl->kernel("dfg.cl", "noSuchKernel"), ibl::Error);
}

TEST(OpenCL, DeviceSelection) {
    if (ibl::ocl::listDevices().empty()) GTEST_SKIP() << "no OpenCL device";
    EXPECT_THROW(ibl::ocl::Context::create("no-device-is-called-this"), ibl::Error);
    auto byIndex = ibl::ocl::Context::create("0:0");
    EXPECT_EQ(byIndex->device().id(), "0:0");
    std::ostringstream warnings;
    EXPECT_THROW(ibl::Executor::create(ibl::Backend::Auto, "no-device-is-called-this", warnings), ibl::Error);
    EXPECT_EQ(ibl::Executor::create(ibl::Backend::Cpu, "", warnings).backend(), ibl::Backend::Cpu);
    EXPECT_TRUE(warnings.str().empty());
}

} // namespace
