#include "iblbake/core/error.h"
#include "iblbake/opencl/opencl_context.h"
#include "program_binaries.h"

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cstdlib>
#include <iterator>
#include <limits>
#include <mutex>

namespace ibl::ocl {
namespace {

std::string clFailure(const cl::Error& e) {
    return std::string(e.what()) + " failed: " + errorName(e.err()) + " (" + std::to_string(e.err()) + ")";
}

std::string lower(std::string s) {
    std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return s;
}

std::string typeName(cl_device_type type) {
    if (type & CL_DEVICE_TYPE_GPU) return "GPU";
    if (type & CL_DEVICE_TYPE_CPU) return "CPU";
    if (type & CL_DEVICE_TYPE_ACCELERATOR) return "ACCELERATOR";
    return "OTHER";
}

struct Candidate {
    cl::Device device;
    DeviceInfo info;
};

std::vector<Candidate> enumerate() {
    // Serialised: two threads making their first executors at once (`iblbake batch --jobs 2`) crashed with
    // SIGSEGV or found no platform in 5 of 5 runs here (ocl-icd loader + PoCL), as the loader sets up its
    // platforms on the first call; with this lock 8 of 8 runs were clean.
    static std::mutex firstCallMutex;
    std::lock_guard lock(firstCallMutex);
    std::vector<Candidate> out;
    std::vector<cl::Platform> platforms;
    try {
        cl::Platform::get(&platforms);
    } catch (const cl::Error&) {
        return out; // no ICD / no platform: the caller falls back or reports "no device"
    }
    for (std::size_t p = 0; p < platforms.size(); ++p) {
        std::vector<cl::Device> devices;
        try {
            platforms[p].getDevices(CL_DEVICE_TYPE_ALL, &devices);
        } catch (const cl::Error&) {
            continue;
        }
        for (std::size_t d = 0; d < devices.size(); ++d) {
            DeviceInfo info;
            info.platformIndex = p;
            info.deviceIndex = d;
            info.platformName = platforms[p].getInfo<CL_PLATFORM_NAME>();
            info.deviceName = devices[d].getInfo<CL_DEVICE_NAME>();
            info.deviceType = typeName(devices[d].getInfo<CL_DEVICE_TYPE>());
            info.deviceVersion = devices[d].getInfo<CL_DEVICE_VERSION>();
            info.computeUnits = devices[d].getInfo<CL_DEVICE_MAX_COMPUTE_UNITS>();
            info.globalMemBytes = devices[d].getInfo<CL_DEVICE_GLOBAL_MEM_SIZE>();
            info.hostUnifiedMemory = devices[d].getInfo<CL_DEVICE_HOST_UNIFIED_MEMORY>() == CL_TRUE;
            out.push_back({devices[d], info});
        }
    }
    return out;
}

} // namespace

std::vector<DeviceInfo> listDevices() {
    std::vector<DeviceInfo> out;
    for (const Candidate& c : enumerate())
        out.push_back(c.info);
    return out;
}

std::shared_ptr<Context> Context::create(const std::string& requested) {
    std::string selector = requested;
    if (selector.empty())
        if (const char* env = std::getenv("IBLBAKE_CL_DEVICE")) selector = env;
    std::vector<Candidate> all = enumerate();
    if (all.empty())
        throw Error("OpenCL: no platform or device found (is an ICD such as pocl-opencl-icd installed?)");

    const Candidate* chosen = nullptr;
    if (selector.empty()) {
        auto gpu = std::find_if(all.begin(), all.end(),
                                [](const Candidate& c) { return c.info.deviceType == "GPU"; });
        chosen = gpu != all.end() ? &*gpu : &all.front();
    } else {
        for (const Candidate& c : all)
            if (c.info.id() == selector ||
                lower(c.info.deviceName).find(lower(selector)) != std::string::npos ||
                lower(c.info.platformName).find(lower(selector)) != std::string::npos) {
                chosen = &c;
                break;
            }
        if (!chosen)
            throw Error("OpenCL: no device matches '" + selector + "' (see 'iblbake devices' for the list)");
    }
    return std::shared_ptr<Context>(new Context(chosen->device, chosen->info));
}

Context::Context(cl::Device device, DeviceInfo info) : device_(device), info_(std::move(info)) {
    baseOptions_ = "-cl-std=CL1.2";
    if (info_.deviceType == "CPU") baseOptions_ += " -DIBL_UNIFORM_LOOP_BARRIER";
    try {
        context_ = cl::Context(device_);
        queue_ = cl::CommandQueue(context_, device_, CL_QUEUE_PROFILING_ENABLE);
    } catch (const cl::Error& e) {
        throw Error("OpenCL device " + info_.deviceName + ": " + clFailure(e));
    }
}

cl::Program Context::buildProgram(const std::string& name, const std::string& source,
                                  const std::string& options) {
    cl::Program program;
    try {
        program = cl::Program(context_, source);
    } catch (const cl::Error& e) {
        throw Error("OpenCL program " + name + ": " + clFailure(e));
    }
    try {
        program.build({device_}, options.c_str());
    } catch (const cl::Error& e) {
        std::string log;
        try {
            log = program.getBuildInfo<CL_PROGRAM_BUILD_LOG>(device_);
        } catch (const cl::Error&) {
            log = "(build log unavailable)";
        }
        // The log is multi-line by nature; it is the one message allowed to span lines.
        throw Error("OpenCL program " + name + " failed to build on " + info_.deviceName + " with options '" +
                    options + "': " + errorName(e.err()) + "\n" + log);
    }
    return program;
}

cl::Program& Context::program(const std::string& file, const std::string& options) {
    std::lock_guard lock(mutex_);
    std::string key = file + '\n' + options;
    auto it = programs_.find(key);
    if (it != programs_.end()) return it->second;
    const std::string source = assembleProgramSource(file), buildOptions = baseOptions_ + " " + options;
    if (binaryDirectories_.empty()) {
        ++builds_.fromSource;
        return programs_.emplace(key, buildProgram(file, source, buildOptions)).first->second;
    }
    const std::string binaryKey = programBinaryKey(device_, buildOptions, source);
    std::vector<std::filesystem::path> lacking;
    for (const std::filesystem::path& directory : binaryDirectories_) {
        if (const std::optional<ProgramBinary> binary = readProgramBinary(directory, binaryKey)) try {
                cl::Program program(context_, {device_}, cl::Program::Binaries{*binary});
                program.build({device_}, buildOptions.c_str());
                ++builds_.fromBinary;
                if (!lacking.empty()) unstoredBinaries_[binaryKey] = {*binary, lacking};
                return programs_.emplace(key, program).first->second;
            } catch (const cl::Error&) { // the driver refused it (another build of the driver): rebuild
            }
        lacking.push_back(directory);
    }
    const auto compileStart = std::chrono::steady_clock::now();
    if (compileObserver_)
        compileObserver_(file, compiledBytes_ > 0.0 ? compileSeconds_ / compiledBytes_ * double(source.size())
                                                    : -1.0);
    cl::Program program = buildProgram(file, source, buildOptions);
    ++builds_.fromSource;
    compiledBytes_ += double(source.size());
    compileSeconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - compileStart).count();
    try {
        const std::vector<ProgramBinary> binaries = program.getInfo<CL_PROGRAM_BINARIES>();
        if (binaries.size() == 1 && !binaries.front().empty())
            unstoredBinaries_[binaryKey] = {binaries.front(), binaryDirectories_};
    } catch (const cl::Error&) { // a driver without binaries: nothing to keep
    }
    return programs_.emplace(key, program).first->second;
}

void Context::useProgramBinaries(std::filesystem::path directory) {
    useProgramBinaries(std::vector<std::filesystem::path>{std::move(directory)});
}

void Context::useProgramBinaries(std::vector<std::filesystem::path> directories) {
    std::lock_guard lock(mutex_);
    binaryDirectories_ = std::move(directories);
}

void Context::storeProgramBinaries() {
    std::lock_guard lock(mutex_);
    for (const auto& [binaryKey, unstored] : unstoredBinaries_)
        for (const std::filesystem::path& directory : unstored.directories)
            writeProgramBinary(directory, binaryKey, unstored.binary);
    unstoredBinaries_.clear();
}

void Context::setCompileObserver(std::function<void(const std::string& file, double seconds)> observer) {
    std::lock_guard lock(mutex_);
    compileObserver_ = std::move(observer);
}

Context::ProgramBuilds Context::programBuilds() const {
    std::lock_guard lock(mutex_);
    return builds_;
}

cl::Kernel Context::kernel(const std::string& file, const std::string& kernelName,
                           const std::string& options) {
    cl::Program& prog = program(file, options);
    try {
        return cl::Kernel(prog, kernelName.c_str());
    } catch (const cl::Error& e) {
        throw Error("OpenCL kernel " + kernelName + " in " + file + ": " + clFailure(e));
    }
}

cl::Buffer Context::createBuffer(cl_mem_flags flags, std::size_t bytes, const void* hostData) {
    // OpenCL has no empty buffers: an empty upload becomes a 16-byte placeholder with nothing to copy.
    if (bytes == 0) {
        flags &= ~cl_mem_flags(CL_MEM_COPY_HOST_PTR | CL_MEM_USE_HOST_PTR);
        hostData = nullptr;
    }
    try {
        return cl::Buffer(context_, flags, std::max<std::size_t>(bytes, 16), const_cast<void*>(hostData));
    } catch (const cl::Error& e) {
        throw Error("OpenCL buffer of " + std::to_string(bytes) + " bytes on " + info_.deviceName + ": " +
                    clFailure(e));
    }
}

void Context::download(const cl::Buffer& buffer, std::size_t bytes, void* destination) {
    finishRead(startRead(buffer, bytes, destination));
}

namespace {

std::string readFailure(std::size_t bytes, const std::string& deviceName, const cl::Error& e) {
    return "OpenCL read of " + std::to_string(bytes) + " bytes from " + deviceName + ": " + clFailure(e);
}

} // namespace

Context::PendingRead Context::startRead(const cl::Buffer& buffer, std::size_t bytes, void* destination) {
    PendingRead read;
    read.bytes = bytes;
    {
        std::lock_guard lock(mutex_);
        read.kernelsBefore = kernelsRun_;
    }
    try {
        queue_.enqueueReadBuffer(buffer, CL_FALSE, 0, bytes, destination, nullptr, &read.event);
        queue_.flush();
    } catch (const cl::Error& e) {
        // A kernel's failure first: the read may only be its consequence.
        waitForPending(read.kernelsBefore, nullptr, nullptr);
        throw Error(readFailure(bytes, info_.deviceName, e));
    }
    return read;
}

void Context::finishRead(const PendingRead& read) {
    waitForPending(read.kernelsBefore, &read.event,
                   [&](const cl::Error& e) { return readFailure(read.bytes, info_.deviceName, e); });
}

void Context::waitForQueue() noexcept {
    try {
        queue_.finish();
    } catch (...) {
    }
}

void Context::run(cl::Kernel& kernel, const cl::NDRange& global, const cl::NDRange& local) {
    std::string name = kernel.getInfo<CL_KERNEL_FUNCTION_NAME>();
    try {
        cl::Event event;
        queue_.enqueueNDRangeKernel(kernel, cl::NullRange, global, local, nullptr, &event);
        queue_.flush(); // started now, not when the read is enqueued
        std::lock_guard lock(mutex_);
        pending_.push_back({std::move(name), std::move(event), kernelsRun_++});
    } catch (const cl::Error& e) {
        throw Error("OpenCL kernel " + name + " on " + info_.deviceName + ": " + clFailure(e));
    }
}

void Context::waitForPending(std::uint64_t before, const cl::Event* last,
                             const std::function<std::string(const cl::Error&)>& failure) {
    std::vector<PendingDispatch> pending;
    {
        std::lock_guard lock(mutex_);
        const auto end = std::find_if(pending_.begin(), pending_.end(),
                                      [&](const PendingDispatch& p) { return p.sequence >= before; });
        pending.assign(std::make_move_iterator(pending_.begin()), std::make_move_iterator(end));
        pending_.erase(pending_.begin(), end);
    }
    std::vector<cl::Event> events;
    for (const PendingDispatch& p : pending)
        events.push_back(p.event);
    if (last) events.push_back(*last);
    if (events.empty()) return;
    // One wait for all. When it reports a failure, each event's own status says whose it was.
    try {
        cl::Event::waitForEvents(events);
    } catch (const cl::Error&) {
    }
    std::vector<DispatchTiming> done;
    for (const PendingDispatch& p : pending) {
        try {
            if (const cl_int status = p.event.getInfo<CL_EVENT_COMMAND_EXECUTION_STATUS>(); status < 0)
                throw cl::Error(status, "clEnqueueNDRangeKernel");
            done.push_back({p.kernel, double(p.event.getProfilingInfo<CL_PROFILING_COMMAND_END>() -
                                             p.event.getProfilingInfo<CL_PROFILING_COMMAND_START>()) *
                                          1e-6});
        } catch (const cl::Error& e) {
            throw Error("OpenCL kernel " + p.kernel + " on " + info_.deviceName + ": " + clFailure(e));
        }
    }
    {
        std::lock_guard lock(mutex_);
        timings_.insert(timings_.end(), done.begin(), done.end());
    }
    if (last) try {
            if (const cl_int status = last->getInfo<CL_EVENT_COMMAND_EXECUTION_STATUS>(); status < 0)
                throw cl::Error(status, "clEnqueueReadBuffer");
        } catch (const cl::Error& e) {
            throw Error(failure(e));
        }
}

std::vector<DispatchTiming> Context::takeTimings() {
    waitForPending(std::numeric_limits<std::uint64_t>::max(), nullptr, nullptr);
    std::lock_guard lock(mutex_);
    return std::exchange(timings_, {});
}

} // namespace ibl::ocl
