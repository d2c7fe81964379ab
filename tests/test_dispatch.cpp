// The dispatch helper (iblbake/opencl/dispatch.h) on its own: grids whose sizes are not multiples of the
// work-group (odd cube faces, 1x1 faces, short rows and lists), on both backends. Every element must be
// stored once with its own coordinates and incremented once, and OpenCL and the CPU must agree exactly.
#include <iblbake/core/error.h>
#include <iblbake/opencl/dispatch.h>
#include <iblbake/opencl/opencl_context.h>

#include <dispatch_check.h>

#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <vector>

namespace {

struct GridCase {
    std::string shape; // "Cube", "Image" or "List": the kernels' names in dispatch_check.cl
    ibl::DispatchGrid grid;
    ibl::DispatchCheckParams params;
};

std::vector<GridCase> gridCases() {
    std::vector<GridCase> cases;
    for (std::uint32_t n : {1u, 2u, 3u, 15u, 16u, 17u, 33u})
        cases.push_back({"Cube", ibl::DispatchGrid::cube(n), {n, 1}});
    for (auto [w, h] : {std::pair{1u, 1u}, {3u, 5u}, {31u, 2u}, {32u, 1u}, {33u, 3u}, {70u, 7u}})
        cases.push_back({"Image", ibl::DispatchGrid::image(w, h), {w, h}});
    for (std::uint32_t count : {1u, 63u, 64u, 65u, 257u, 1000u})
        cases.push_back({"List", ibl::DispatchGrid::list(count), {count, 1}});
    return cases;
}

// Distinct per element, exact in fp32, so that a wrong element or a second add cannot cancel out.
std::vector<float> increments(std::size_t elementCount) {
    std::vector<float> values;
    for (std::size_t i = 0; i < elementCount; ++i)
        values.insert(values.end(), {1000.0f * float(i + 1), 0.5f, 0.25f * float(i), 7.0f});
    return values;
}

std::vector<glm::vec4> runCheck(const ibl::Dispatcher& dispatcher, const GridCase& c) {
    const std::string store = "check" + c.shape + "Store", add = "check" + c.shape + "Add";
    const auto storeKernel = ibl::kernel("dispatch_check.cl", store.c_str(), ibl::dispatchCheckStoreItem);
    const auto addKernel = ibl::kernel("dispatch_check.cl", add.c_str(), ibl::dispatchCheckAddItem);
    const std::vector<float> added = increments(c.grid.elementCount());
    ibl::DispatchOutput out = dispatcher.output(c.grid);
    dispatcher.run(storeKernel, out, c.params);
    // The increments go through a second output used as an input, as a chunked accumulation does.
    ibl::DispatchOutput increment = dispatcher.output(c.grid);
    dispatcher.run(storeKernel, increment, c.params);
    dispatcher.run(addKernel, increment, c.params, dispatcher.upload("increments", added));
    dispatcher.run(addKernel, out, c.params, increment.asInput());
    return dispatcher.download(out);
}

// Element i at (x, y, face) is stored as (x, y, face, 4 i); the increment output holds (x, y, face) plus
// increments i, and it is added once (to RGB only).
glm::vec4 expected(const GridCase& c, const std::vector<float>& added, std::size_t i) {
    const std::uint32_t w = c.params.width, h = c.shape == "Cube" ? w : c.params.height;
    const float x = float(i % w), y = float(i / w % h), face = float(i / (std::size_t(w) * h));
    return {2.0f * x + added[4 * i], 2.0f * y + added[4 * i + 1], 2.0f * face + added[4 * i + 2],
            float(4 * i)};
}

TEST(Dispatch, EveryElementWrittenOnceOnTheCpu) {
    for (const GridCase& c : gridCases()) {
        const std::vector<glm::vec4> out = runCheck(ibl::Dispatcher(nullptr), c);
        const std::vector<float> added = increments(c.grid.elementCount());
        ASSERT_EQ(out.size(), c.grid.elementCount());
        for (std::size_t i = 0; i < out.size(); ++i)
            ASSERT_EQ(out[i], expected(c, added, i))
                << c.shape << " " << c.params.width << "x" << c.params.height << ", element " << i;
    }
}

TEST(Dispatch, OpenCLMatchesTheCpuExactly) {
    if (ibl::ocl::listDevices().empty()) GTEST_SKIP() << "no OpenCL device";
    std::shared_ptr<ibl::ocl::Context> cl = ibl::ocl::Context::create();
    for (const GridCase& c : gridCases()) {
        const std::vector<glm::vec4> gpu = runCheck(ibl::Dispatcher(cl.get()), c);
        const std::vector<glm::vec4> cpu = runCheck(ibl::Dispatcher(nullptr), c);
        ASSERT_EQ(gpu.size(), cpu.size());
        for (std::size_t i = 0; i < gpu.size(); ++i)
            ASSERT_EQ(gpu[i], cpu[i])
                << c.shape << " " << c.params.width << "x" << c.params.height << ", element " << i;
    }
}

TEST(Dispatch, CubeOutputIsFaceByFace) {
    const ibl::Dispatcher cpu(nullptr);
    const GridCase c{"Cube", ibl::DispatchGrid::cube(3), {3, 1}};
    ibl::DispatchOutput out = cpu.output(c.grid);
    cpu.run(ibl::kernel("dispatch_check.cl", "checkCubeStore", ibl::dispatchCheckStoreItem), out, c.params);
    const ibl::CubeMap cube = cpu.downloadCube(out);
    for (int f = 0; f < 6; ++f)
        for (int y = 0; y < 3; ++y)
            for (int x = 0; x < 3; ++x)
                EXPECT_EQ(cube.faces[f].at(x, y), glm::vec4(x, y, f, 4 * ((f * 3 + y) * 3 + x)));
}

// An unknown entry point, and an entry point whose arguments are not the item function's (checkListStore
// takes no increments), are errors that name the entry point instead of a crash or a wrong result.
TEST(Dispatch, MismatchedEntryPointsAreErrors) {
    if (ibl::ocl::listDevices().empty()) GTEST_SKIP() << "no OpenCL device";
    std::shared_ptr<ibl::ocl::Context> cl = ibl::ocl::Context::create();
    const ibl::Dispatcher dispatcher(cl.get());
    ibl::DispatchOutput out = dispatcher.output(ibl::DispatchGrid::list(4));
    const ibl::DispatchCheckParams params{4, 1};
    const std::vector<float> added = increments(4);
    auto expectError = [&](auto&& run, const std::string& entryPoint) {
        try {
            run();
            ADD_FAILURE() << entryPoint << " ran";
        } catch (const ibl::Error& e) {
            EXPECT_NE(std::string(e.what()).find(entryPoint), std::string::npos) << e.what();
        }
    };
    expectError(
        [&] {
            dispatcher.run(ibl::kernel("dispatch_check.cl", "noSuchEntry", ibl::dispatchCheckStoreItem), out,
                           params);
        },
        "noSuchEntry");
    expectError(
        [&] {
            dispatcher.run(ibl::kernel("dispatch_check.cl", "checkListStore", ibl::dispatchCheckAddItem), out,
                           params, dispatcher.upload("increments", added));
        },
        "checkListStore");
}

} // namespace
