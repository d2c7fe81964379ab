// The OpenCL host layer: diagnostics that name the program, device, options and carry the build log.
#include <iblbake/core/error.h>
#include <iblbake/opencl/executor.h>
#include <iblbake/opencl/opencl_context.h>

#include <gtest/gtest.h>

#include <sstream>
#include <string>
#include <vector>

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

// Kernels are enqueued without a wait each (Context::run): the in-order queue still runs them in turn before
// the read, and the read's one wait records every kernel's device time, in order.
TEST(OpenCL, KernelsRunInOrderBeforeTheReadAndAreTimed) {
    auto cl = contextOrSkip();
    if (!cl) GTEST_SKIP() << "no OpenCL device";
    const std::string source = "__kernel void addOne(__global float* v) { v[get_global_id(0)] += 1.0f; }\n"
                               "__kernel void twice(__global float* v) { v[get_global_id(0)] *= 2.0f; }\n";
    cl::Program program = cl->buildProgram("order.cl", source, "");
    cl::Kernel addOne(program, "addOne"), twice(program, "twice");
    std::vector<float> values(1024);
    for (std::size_t i = 0; i < values.size(); ++i)
        values[i] = float(i);
    cl::Buffer buffer = cl->createBuffer(CL_MEM_READ_WRITE | CL_MEM_COPY_HOST_PTR,
                                         values.size() * sizeof(float), values.data());
    addOne.setArg(0, buffer);
    twice.setArg(0, buffer);
    cl->takeTimings();
    cl->run(addOne, cl::NDRange(values.size()));
    cl->run(twice, cl::NDRange(values.size()));
    cl->run(twice, cl::NDRange(values.size()));
    std::vector<float> read(values.size());
    cl->download(buffer, read.size() * sizeof(float), read.data());
    for (std::size_t i = 0; i < values.size(); ++i)
        ASSERT_EQ(read[i], (float(i) + 1.0f) * 4.0f) << i;
    const std::vector<ibl::ocl::DispatchTiming> timings = cl->takeTimings();
    ASSERT_EQ(timings.size(), 3u);
    EXPECT_EQ(timings[0].kernel, "addOne");
    EXPECT_EQ(timings[1].kernel, "twice");
    EXPECT_EQ(timings[2].kernel, "twice");
    for (const ibl::ocl::DispatchTiming& t : timings)
        EXPECT_GE(t.milliseconds, 0.0);
    // A launch the device refuses is the kernel's own error, at once.
    try {
        cl->run(addOne, cl::NDRange(values.size()), cl::NDRange(values.size() + 1));
        FAIL() << "a work-group larger than the range was enqueued";
    } catch (const ibl::Error& e) {
        EXPECT_NE(std::string(e.what()).find("OpenCL kernel addOne"), std::string::npos) << e.what();
    }
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
