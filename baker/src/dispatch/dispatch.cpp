#include "iblbake/opencl/dispatch.h"
#include "iblbake/core/error.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cstring>
#include <utility>

namespace ibl {
namespace {

// A list's CPU range: enough work per task to hide TBB's overhead on light elements (shaded points).
constexpr std::size_t kListRange = 256;

std::size_t roundUp(std::size_t value, std::size_t multiple) {
    return (value + multiple - 1) / multiple * multiple;
}

} // namespace

DispatchGrid DispatchGrid::cube(std::uint32_t faceSize) {
    return DispatchGrid(Shape::Cube, faceSize, faceSize, 6, std::min<std::uint32_t>(16, faceSize));
}

DispatchGrid DispatchGrid::image(std::uint32_t width, std::uint32_t height) {
    return DispatchGrid(Shape::Image, width, height, 1, 32);
}

DispatchGrid DispatchGrid::list(std::size_t count) {
    return DispatchGrid(Shape::List, std::uint32_t(count), 1, 1, 64);
}

WorkItem DispatchGrid::itemAt(std::size_t element) const {
    const std::uint32_t x = std::uint32_t(element % width_);
    const std::size_t row = element / width_;
    switch (shape_) {
    case Shape::Cube:
        return cubeWorkItemAt(x, std::uint32_t(row % height_), std::uint32_t(row / height_), width_);
    case Shape::Image:
        return imageWorkItemAt(x, std::uint32_t(row), width_, height_);
    default:
        return listWorkItemAt(x, width_);
    }
}

void DispatchGrid::forEachRange(const std::function<void(std::size_t first, std::size_t end)>& range) const {
    const std::size_t count = elementCount();
    const std::size_t length = shape_ == Shape::List ? kListRange : width_;
    const std::size_t ranges = (count + length - 1) / length;
    tbb::parallel_for(std::size_t(0), ranges,
                      [&](std::size_t r) { range(r * length, std::min(count, (r + 1) * length)); });
}

cl::NDRange DispatchGrid::globalRange() const {
    const std::size_t width = roundUp(width_, groupWidth_);
    switch (shape_) {
    case Shape::Cube:
        return cl::NDRange(width, height_, layers_);
    case Shape::Image:
        return cl::NDRange(width, height_);
    default:
        return cl::NDRange(width);
    }
}

cl::NDRange DispatchGrid::localRange() const {
    switch (shape_) {
    case Shape::Cube:
        return cl::NDRange(groupWidth_, 1, 1);
    case Shape::Image:
        return cl::NDRange(groupWidth_, 1);
    default:
        return cl::NDRange(groupWidth_);
    }
}

DeviceArray<float> DispatchOutput::asInput() const {
    DeviceArray<float> array;
    array.host_ = host_.data();
    array.buffer_ = buffer_;
    return array;
}

cl::Buffer Dispatcher::uploadBytes(const std::string& name, const void* data, std::size_t bytes,
                                   bool shared) const {
    const bool inPlace = shared && cl_->device().hostUnifiedMemory;
    try {
        return cl_->createBuffer(CL_MEM_READ_ONLY | (inPlace ? CL_MEM_USE_HOST_PTR : CL_MEM_COPY_HOST_PTR),
                                 bytes, data);
    } catch (const Error& e) {
        throw Error(name + ": " + e.what());
    }
}

DispatchOutput Dispatcher::output(const DispatchGrid& grid) const {
    DispatchOutput out(grid);
    const std::size_t floats = grid.elementCount() * IBL_OUTPUT_FLOATS;
    if (cl_)
        out.buffer_ = cl_->createBuffer(CL_MEM_READ_WRITE, floats * sizeof(float));
    else
        out.host_.resize(floats);
    return out;
}

std::vector<glm::vec4> Dispatcher::download(const DispatchOutput& out) const {
    return finishElements(startDownload(out));
}

std::vector<glm::vec4> Dispatcher::finishElements(PendingDownload pending) const {
    if (pending.read_) {
        cl_->finishRead(*pending.read_);
        pending.read_.reset();
    }
    return std::move(pending.elements_);
}

PendingDownload Dispatcher::startDownload(const DispatchOutput& out) const {
    static_assert(sizeof(glm::vec4) == IBL_OUTPUT_FLOATS * sizeof(float));
    PendingDownload pending(cl_, out.grid());
    pending.elements_.resize(out.grid().elementCount());
    if (pending.elements_.empty()) return pending;
    if (cl_)
        pending.read_ = cl_->startRead(out.buffer_, pending.elements_.size() * sizeof(glm::vec4),
                                       pending.elements_.data());
    else
        std::memcpy(pending.elements_.data(), out.host_.data(), out.host_.size() * sizeof(float));
    return pending;
}

// The read's destination is the elements' heap block, which a move hands over as it is.
PendingDownload::PendingDownload(PendingDownload&& other) noexcept
    : cl_(other.cl_), grid_(other.grid_), elements_(std::move(other.elements_)),
      read_(std::exchange(other.read_, std::nullopt)) {}

PendingDownload::~PendingDownload() {
    if (read_) cl_->waitForQueue();
}

CubeMap Dispatcher::finishCube(PendingDownload pending) const {
    const int n = int(pending.grid_.width());
    const std::vector<glm::vec4> texels = finishElements(std::move(pending));
    const std::size_t faceTexels = std::size_t(n) * std::size_t(n);
    CubeMap cube(n);
    for (std::size_t f = 0; f < 6; ++f)
        std::copy(texels.begin() + std::ptrdiff_t(f * faceTexels),
                  texels.begin() + std::ptrdiff_t((f + 1) * faceTexels), cube.faces[f].pixels.begin());
    return cube;
}

CubeMap Dispatcher::downloadCube(const DispatchOutput& out) const {
    return finishCube(startDownload(out));
}

void Dispatcher::waitForDevice() const noexcept {
    if (cl_) cl_->waitForQueue();
}

ImageRGBA Dispatcher::downloadImage(const DispatchOutput& out) const {
    ImageRGBA image(int(out.grid().width()), int(out.grid().height()));
    image.pixels = download(out);
    return image;
}

void Dispatcher::checkArgumentCount(const cl::Kernel& k, const char* file, const char* entryPoint,
                                    std::size_t count) {
    const cl_uint declared = k.getInfo<CL_KERNEL_NUM_ARGS>();
    if (declared != count)
        throw Error(std::string("OpenCL kernel ") + entryPoint + " in kernels/" + file + " takes " +
                    std::to_string(declared) + " arguments, its work-item function " + std::to_string(count));
}

void Dispatcher::throwSetArgFailure(const char* entryPoint, cl_uint index, cl_int status) {
    throw Error(std::string("OpenCL kernel ") + entryPoint + ": setting argument " + std::to_string(index) +
                " failed: " + ocl::errorName(status));
}

} // namespace ibl
