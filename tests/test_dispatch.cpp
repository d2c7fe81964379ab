// The dispatch helper (iblbake/opencl/dispatch.h) on its own: grids whose sizes are not multiples of the
// work-group (odd cube faces, 1x1 faces, short rows and lists), on both backends. Every element must be
// stored once with its own coordinates and incremented once, and OpenCL and the CPU must agree exactly.
#include <iblbake/core/error.h>
#include <iblbake/opencl/dispatch.h>
#include <iblbake/opencl/executor.h>
#include <iblbake/opencl/opencl_context.h>

#include <dispatch_check.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <string>
#include <vector>

namespace {

struct GridCase {
    std::string shape; // "Cube", "StridedCube", "Image" or "List": the kernels' names in dispatch_check.cl
    ibl::DispatchGrid grid;
    ibl::DispatchCheckParams params;
};

std::vector<GridCase> gridCases() {
    std::vector<GridCase> cases;
    for (std::uint32_t n : {1u, 2u, 3u, 15u, 16u, 17u, 33u})
        for (const char* shape : {"Cube", "StridedCube"}) // the same grid, rows in another order on OpenCL
            cases.push_back({shape, ibl::DispatchGrid::cube(n), {n, 1}});
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
    const std::uint32_t w = c.params.width, h = c.shape.ends_with("Cube") ? w : c.params.height;
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

// startDownload / finishCube (a chain's levels on OpenCL: level m + 1 is enqueued before level m is read): a
// download holds its output as it was when the download started, though the output is changed and other
// outputs are written and read after it and the downloads finish in the other order; one dropped unfinished
// leaves the dispatcher usable. On both backends.
TEST(Dispatch, StartedDownloadsHoldTheirOutputsAsTheyWere) {
    std::vector<std::shared_ptr<ibl::ocl::Context>> contexts{nullptr};
    if (!ibl::ocl::listDevices().empty()) contexts.push_back(ibl::ocl::Context::create());
    for (const std::shared_ptr<ibl::ocl::Context>& cl : contexts) {
        SCOPED_TRACE(cl ? "opencl" : "cpu");
        const ibl::Dispatcher dispatcher(cl.get());
        const GridCase c{"Cube", ibl::DispatchGrid::cube(5), {5, 1}};
        const auto store = ibl::kernel("dispatch_check.cl", "checkCubeStore", ibl::dispatchCheckStoreItem);
        const auto add = ibl::kernel("dispatch_check.cl", "checkCubeAdd", ibl::dispatchCheckAddItem);
        const std::vector<float> added = increments(c.grid.elementCount());
        const ibl::DeviceArray<float> addedData = dispatcher.upload("increments", added);
        ibl::DispatchOutput first = dispatcher.output(c.grid), second = dispatcher.output(c.grid);
        dispatcher.run(store, first, c.params);
        ibl::PendingDownload firstStored = dispatcher.startDownload(first);
        dispatcher.run(add, first, c.params, addedData); // after the read: not in it
        dispatcher.run(store, second, c.params);
        dispatcher.run(add, second, c.params, addedData);
        ibl::PendingDownload secondAdded = dispatcher.startDownload(second);
        { ibl::PendingDownload dropped = dispatcher.startDownload(first); }
        const ibl::CubeMap secondCube = dispatcher.finishCube(std::move(secondAdded));
        const ibl::CubeMap firstCube = dispatcher.finishCube(std::move(firstStored));
        for (int f = 0; f < 6; ++f)
            for (int y = 0; y < 5; ++y)
                for (int x = 0; x < 5; ++x) {
                    const std::size_t i = std::size_t((f * 5 + y) * 5 + x);
                    EXPECT_EQ(firstCube.faces[f].at(x, y), glm::vec4(x, y, f, 4 * i));
                    EXPECT_EQ(secondCube.faces[f].at(x, y),
                              glm::vec4(float(x) + added[4 * i], float(y) + added[4 * i + 1],
                                        float(f) + added[4 * i + 2], 4 * i));
                }
        // Still usable: the first output now holds the add.
        const ibl::CubeMap firstAfter = dispatcher.downloadCube(first);
        EXPECT_EQ(firstAfter.faces[5].at(4, 4), glm::vec4(4.0f + added[4 * 149], 4.0f + added[4 * 149 + 1],
                                                          5.0f + added[4 * 149 + 2], 4 * 149));
        if (cl) EXPECT_EQ(cl->takeTimings().size(), 4u); // every kernel waited for and timed once
    }
}

// The CPU backend times its dispatches as OpenCL does (Executor::takeTimings: `--timing`, bench
// bakeChainLevels): one entry per dispatch, in order, named by entry point; taking them empties the list.
TEST(Dispatch, CpuDispatchesAreTimedInOrder) {
    const ibl::Executor executor = ibl::Executor::cpu();
    const GridCase c{"Cube", ibl::DispatchGrid::cube(17), {17, 1}};
    EXPECT_EQ(runCheck(ibl::Dispatcher(executor), c), runCheck(ibl::Dispatcher(nullptr), c));
    const std::vector<ibl::ocl::DispatchTiming> timings = executor.takeTimings();
    const std::vector<std::string> expectedOrder{"checkCubeStore", "checkCubeStore", "checkCubeAdd",
                                                 "checkCubeAdd"};
    ASSERT_EQ(timings.size(), expectedOrder.size());
    for (std::size_t i = 0; i < timings.size(); ++i) {
        EXPECT_EQ(timings[i].kernel, expectedOrder[i]);
        EXPECT_GE(timings[i].milliseconds, 0.0);
    }
    EXPECT_TRUE(executor.takeTimings().empty());
}

// cubeWorkItemStrided's order: every row of the level once, and rows that follow each other in the dispatch
// at least a quarter of the level apart (in the cyclic order of rows), at every face size a chain has and at
// odd ones.
TEST(Dispatch, StridedCubeRowsArePermutationsThatSpreadNeighbours) {
    std::vector<std::uint32_t> sizes{3, 5, 7, 15, 17, 33, 100, 1000};
    for (std::uint32_t n = 1; n <= 8192; n *= 2)
        sizes.push_back(n);
    for (std::uint32_t n : sizes) {
        const std::uint32_t rows = 6 * n;
        std::vector<int> taken(rows, 0);
        for (std::uint32_t g = 0; g < rows; ++g) {
            const std::uint32_t row = ibl::cubeStridedRow(g, n);
            ASSERT_LT(row, rows) << "n " << n << ", g " << g;
            ++taken[row];
            if (n >= 8 && g > 0) {
                const std::uint32_t step = (row + rows - ibl::cubeStridedRow(g - 1, n)) % rows;
                ASSERT_GE(std::min(step, rows - step), rows / 4) << "n " << n << ", g " << g;
            }
        }
        for (std::uint32_t row = 0; row < rows; ++row)
            ASSERT_EQ(taken[row], 1) << "n " << n << ", row " << row;
    }
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
