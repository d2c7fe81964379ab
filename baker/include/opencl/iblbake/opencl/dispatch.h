// One way to run a kernel over a grid on either backend, in the spirit of pbrt-v4's ParallelFor: a stage
// says once what to run (a Kernel), over which elements (a DispatchGrid), with which arguments, and the
// Dispatcher decides how. On OpenCL it uploads the inputs, pads the grid to whole work-groups, launches the
// entry point of kernels/<file> and downloads the output; on the CPU backend it runs TBB over the grid's
// rows and calls, for each element, the very same portable item function the entry point calls
// (kernels/work_item.h), on the host arrays in place. So both backends run one piece of code per element.
//
// Kernel contract: the entry point's arguments are (output, parameter struct, inputs...), it gets its
// WorkItem from the global id and calls the item function with them, nothing else:
//   __kernel void ldBright(__global float* out, LdParams p, __global const float* clusters, ...) {
//       ldBrightItem(cubeWorkItem(p.faceSize), out, p, clusters, ...);
//   }
// An item writes only the 4 output floats it owns (WorkItem::offset), and reads its own output only as
// left by an earlier dispatch: reading it in the sample loop of the same kernel stops PoCL from
// vectorizing (kernels/portable.h), so accumulation goes through a second output and an add kernel.
#pragma once

#include "iblbake/core/cubemap.h"
#include "iblbake/core/image.h"
#include "iblbake/opencl/executor.h"
#include "iblbake/opencl/opencl_context.h"

#include <work_item.h>

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace ibl {

// The elements a dispatch runs over, one work-item each, and how OpenCL groups them.
class DispatchGrid {
  public:
    // The texels of a cube level: 6 faces of faceSize x faceSize, face by face, row by row. A work-group
    // is up to 16 adjacent texels of one row: one face, nearby fetches, uniform loops.
    static DispatchGrid cube(std::uint32_t faceSize);
    // A width x height image, row by row. A work-group is 32 texels of one row (a DFG LUT row shares its
    // roughness, so the items of a group run the same loop and PoCL vectorizes across them).
    static DispatchGrid image(std::uint32_t width, std::uint32_t height);
    // `count` elements in groups of 64.
    static DispatchGrid list(std::size_t count);

    std::size_t elementCount() const { return std::size_t(width_) * height_ * layers_; }
    std::uint32_t width() const { return width_; }
    std::uint32_t height() const { return height_; }
    // The work-item of an element (index in the output's order), as the entry point computes it.
    WorkItem itemAt(std::size_t element) const;
    // Calls `range(first, end)` on TBB threads for element ranges that cover the grid once: a row of a
    // cube face or an image each, or 256 elements of a list.
    void forEachRange(const std::function<void(std::size_t first, std::size_t end)>& range) const;
    cl::NDRange globalRange() const; // padded to whole groups along x
    cl::NDRange localRange() const;

  private:
    enum class Shape { Cube, Image, List };
    DispatchGrid(Shape shape, std::uint32_t width, std::uint32_t height, std::uint32_t layers,
                 std::uint32_t groupWidth)
        : shape_(shape), width_(width), height_(height), layers_(layers), groupWidth_(groupWidth) {}
    Shape shape_;
    std::uint32_t width_, height_, layers_, groupWidth_;
};

// An input of a dispatch: the caller's host array, read in place on the CPU (it must outlive the
// dispatches that use it) or copied once into an OpenCL buffer that every later dispatch shares.
template <class T>
class DeviceArray {
  public:
    DeviceArray() = default;
    const T* host() const { return host_; }
    const cl::Buffer& buffer() const { return buffer_; }

  private:
    friend class Dispatcher;
    friend class DispatchOutput;
    const T* host_ = nullptr;
    cl::Buffer buffer_;
};

// The output of dispatches over one grid: IBL_OUTPUT_FLOATS floats per element, in device memory on
// OpenCL. Its contents are undefined until a kernel stores every element.
class DispatchOutput {
  public:
    const DispatchGrid& grid() const { return grid_; }
    // The output as an input of a later dispatch (e.g. a chunk added into a sum).
    DeviceArray<float> asInput() const;

  private:
    friend class Dispatcher;
    explicit DispatchOutput(const DispatchGrid& grid) : grid_(grid) {}
    DispatchGrid grid_;
    std::vector<float> host_;
    cl::Buffer buffer_;
};

// A download of a DispatchOutput under way (Dispatcher::startDownload): on OpenCL a read enqueued behind the
// output's kernels, on the CPU backend a copy already made. Destroyed unfinished (an error path), it waits
// for the device's queue, so that no read lands in freed memory.
class PendingDownload {
  public:
    PendingDownload(PendingDownload&& other) noexcept;
    PendingDownload& operator=(PendingDownload&&) = delete;
    ~PendingDownload();

  private:
    friend class Dispatcher;
    PendingDownload(ocl::Context* cl, const DispatchGrid& grid) : cl_(cl), grid_(grid) {}
    ocl::Context* cl_;
    DispatchGrid grid_;
    std::vector<glm::vec4> elements_;
    std::optional<ocl::Context::PendingRead> read_; // OpenCL, until finished
};

// A kernel of kernels/<file>: its OpenCL entry point and the portable item function it calls.
template <class Params, class... Inputs>
struct Kernel {
    const char* file;
    const char* entryPoint;
    void (*item)(WorkItem, float*, Params, const Inputs*...);
};

template <class Params, class... Inputs>
Kernel<Params, Inputs...> kernel(const char* file, const char* entryPoint,
                                 void (*item)(WorkItem, float*, Params, const Inputs*...)) {
    return {file, entryPoint, item};
}

class Dispatcher {
  public:
    // The CPU backend's dispatches record their wall times in the executor (Executor::takeTimings).
    explicit Dispatcher(const Executor& executor)
        : cl_(executor.usesOpenCL() ? &executor.cl() : nullptr), cpuTimings_(executor.cpuTimings()) {}
    // nullptr: the CPU backend, untimed.
    explicit Dispatcher(ocl::Context* cl) : cl_(cl) {}

    bool usesOpenCL() const { return cl_ != nullptr; }

    // `name` says which input failed in an error message.
    template <class T>
    DeviceArray<T> upload(const std::string& name, std::span<const T> data) const {
        return deviceArray(name, data, false);
    }
    template <class T>
    DeviceArray<T> upload(const std::string& name, const std::vector<T>& data) const {
        return upload(name, std::span<const T>(data));
    }
    // upload() of a host array the caller keeps, unchanged, until every dispatch that reads it has finished
    // (a download waits for them): a device that shares the host's memory (DeviceInfo::hostUnifiedMemory)
    // reads it where it is (CL_MEM_USE_HOST_PTR) instead of from a copy. The 1k sample's 8 MB specular
    // pyramid on PoCL: no copy, and 11,402 -> 9,831 page faults for the whole `specular` process.
    template <class T>
    DeviceArray<T> share(const std::string& name, const std::vector<T>& data) const {
        return deviceArray(name, std::span<const T>(data), true);
    }

    DispatchOutput output(const DispatchGrid& grid) const;

    // Runs `k` over the output's grid with these arguments.
    template <class Params, class... Inputs>
    void run(const Kernel<Params, Inputs...>& k, DispatchOutput& out, const Params& params,
             const DeviceArray<Inputs>&... inputs) const {
        if (out.grid().elementCount() == 0) return;
        if (!cl_) {
            float* target = out.host_.data();
            const DispatchGrid& grid = out.grid();
            const auto start = std::chrono::steady_clock::now();
            grid.forEachRange([&](std::size_t first, std::size_t end) {
                for (std::size_t element = first; element < end; ++element)
                    k.item(grid.itemAt(element), target, params, inputs.host()...);
            });
            if (cpuTimings_)
                cpuTimings_->record(k.entryPoint, std::chrono::duration<double, std::milli>(
                                                      std::chrono::steady_clock::now() - start)
                                                      .count());
            return;
        }
        cl::Kernel clKernel = cl_->kernel(k.file, k.entryPoint);
        checkArgumentCount(clKernel, k.file, k.entryPoint, 2 + sizeof...(Inputs));
        cl_uint index = 0;
        setArg(clKernel, k.entryPoint, index++, out.buffer_);
        setArg(clKernel, k.entryPoint, index++, params);
        (setArg(clKernel, k.entryPoint, index++, inputs.buffer()), ...);
        cl_->run(clKernel, out.grid().globalRange(), out.grid().localRange());
    }

    // The output, element by element.
    std::vector<glm::vec4> download(const DispatchOutput& out) const;
    // download() in two halves: the host may enqueue more work between them, which an OpenCL device then
    // runs without waiting for the host (a chain's next level). finishCube waits for the read and the
    // kernels before it and gives the output of a cube grid as a cube map.
    PendingDownload startDownload(const DispatchOutput& out) const;
    CubeMap finishCube(PendingDownload pending) const;
    // Waits for every command enqueued on the device, whatever its outcome (an owner of host arrays that
    // dispatches may still read, before it frees them on an error path). Nothing on the CPU backend.
    void waitForDevice() const noexcept;
    // The output of a cube grid as a cube map; of an image grid as an image.
    CubeMap downloadCube(const DispatchOutput& out) const;
    ImageRGBA downloadImage(const DispatchOutput& out) const;

  private:
    // upload() (shared false) or share() (true).
    template <class T>
    DeviceArray<T> deviceArray(const std::string& name, std::span<const T> data, bool shared) const {
        DeviceArray<T> array;
        if (cl_)
            array.buffer_ = uploadBytes(name, data.data(), data.size_bytes(), shared);
        else
            array.host_ = data.data();
        return array;
    }
    std::vector<glm::vec4> finishElements(PendingDownload pending) const;
    cl::Buffer uploadBytes(const std::string& name, const void* data, std::size_t bytes, bool shared) const;
    template <class T>
    static void setArg(cl::Kernel& k, const char* entryPoint, cl_uint index, const T& value) {
        try {
            k.setArg(index, value);
        } catch (const cl::Error& e) {
            throwSetArgFailure(entryPoint, index, e.err());
        }
    }
    // The entry point takes as many arguments as the item function (output, parameters, inputs).
    static void checkArgumentCount(const cl::Kernel& k, const char* file, const char* entryPoint,
                                   std::size_t count);
    [[noreturn]] static void throwSetArgFailure(const char* entryPoint, cl_uint index, cl_int status);

    ocl::Context* cl_;
    CpuDispatchTimings* cpuTimings_ = nullptr;
};

} // namespace ibl
