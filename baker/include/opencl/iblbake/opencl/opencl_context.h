// The OpenCL host layer: device choice, embedded program build with full diagnostics, a per-process
// program cache, and per-dispatch timing. Every kernel goes through this one place, launched by the
// dispatch helper (iblbake/opencl/dispatch.h).
#pragma once

#define CL_HPP_TARGET_OPENCL_VERSION 120
#define CL_HPP_MINIMUM_OPENCL_VERSION 120
#define CL_HPP_ENABLE_EXCEPTIONS
#include <CL/opencl.hpp>

#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

namespace ibl::ocl {

// Symbolic name of an OpenCL status code ("CL_OUT_OF_RESOURCES"), or "CL_UNKNOWN_ERROR".
const char* errorName(cl_int status);

// Where a command without a cache directory of its own (`specular`, `diffuse`, `dfg`, ...) keeps program
// binaries for the user running it (docs/conventions.md "Kernels, backends and kernel binaries"):
// $IBLBAKE_KERNEL_CACHE (set and empty: none), else $XDG_CACHE_HOME/iblbake/kernels, else
// $HOME/.cache/iblbake/kernels (the XDG Base Directory defaults, as PoCL and Mesa keep theirs); nullopt when
// none applies. Relative XDG/HOME values are ignored, as the XDG specification asks.
std::optional<std::filesystem::path> userProgramBinaryDirectory();

struct DeviceInfo {
    std::size_t platformIndex = 0;
    std::size_t deviceIndex = 0;
    std::string platformName;
    std::string deviceName;
    std::string deviceType; // "CPU", "GPU", "ACCELERATOR", ...
    std::string deviceVersion;
    cl_uint computeUnits = 0;
    cl_ulong globalMemBytes = 0;
    bool hostUnifiedMemory = false; // CL_DEVICE_HOST_UNIFIED_MEMORY: a CPU device, an integrated GPU

    std::string id() const { return std::to_string(platformIndex) + ":" + std::to_string(deviceIndex); }
};

// All devices of all platforms; empty when there is no ICD or no device.
std::vector<DeviceInfo> listDevices();

struct DispatchTiming {
    std::string kernel;
    double milliseconds = 0.0; // OpenCL: device execution time from profiling events; CPU backend: wall time
};

// Inserts the embedded headers a source includes (each once), with #line markers so that build logs
// point at kernels/<file>:<line>. Throws ibl::Error naming a missing include.
std::string assembleProgramSource(const std::string& mainFile);

class Context {
  public:
    // selector: "" (use $IBLBAKE_CL_DEVICE, else the first GPU, else the first device), "P:D" indices,
    // or a case-insensitive substring of the device or platform name. Throws ibl::Error when nothing fits.
    static std::shared_ptr<Context> create(const std::string& selector = "");

    const DeviceInfo& device() const { return info_; }
    cl::Context& context() { return context_; }
    cl::CommandQueue& queue() { return queue_; }

    // Options every embedded program is built with: OpenCL C 1.2, plus IBL_UNIFORM_LOOP_BARRIER on CPU
    // devices (see kernels/portable.h).
    const std::string& baseOptions() const { return baseOptions_; }
    // Program from the embedded kernels/<file>, built once per process and options string.
    cl::Program& program(const std::string& file, const std::string& options = "");
    cl::Kernel kernel(const std::string& file, const std::string& kernelName,
                      const std::string& options = "");
    // Builds arbitrary source; on failure throws ibl::Error with program name, device, options and log.
    cl::Program buildProgram(const std::string& name, const std::string& source, const std::string& options);

    // Program binaries kept in `directory` (docs/conventions.md "Kernels, backends and kernel binaries"):
    // from now on an embedded program is loaded from a binary there when one of the same platform, device,
    // driver, options and source is found and builds; otherwise it is built from source and its binary held
    // for storeProgramBinaries().
    void useProgramBinaries(std::filesystem::path directory);
    // The same with several directories (a bake's cache and the user's, userProgramBinaryDirectory): a
    // binary is loaded from the first that holds it, and stored into every one that lacks it, so that a
    // kernel is compiled once per machine and driver, not once per bake (issue 46).
    void useProgramBinaries(std::vector<std::filesystem::path> directories);
    // Writes the binaries built from source since useProgramBinaries (called once a command's outputs are
    // complete, so a failed command adds nothing to a cache), and those loaded from one directory into the
    // others. A directory that cannot be written is skipped: it costs only compile time.
    void storeProgramBinaries();
    // Called before a program is built from source (not loaded from a binary) with its file and an estimate
    // of the seconds it takes (negative before the first build from source: this process's compile rate per
    // byte of source times the program's size), so that a caller can say what it waits on (issue 46).
    void setCompileObserver(std::function<void(const std::string& file, double seconds)> observer);
    struct ProgramBuilds {
        int fromSource = 0, fromBinary = 0;
    };
    ProgramBuilds programBuilds() const;

    // Buffers, with CL failures turned into ibl::Error.
    cl::Buffer createBuffer(cl_mem_flags flags, std::size_t bytes, const void* hostData = nullptr);
    // Reads a buffer after the kernels run before it, in one wait with them; a kernel's failure is thrown
    // as its own (run).
    void download(const cl::Buffer& buffer, std::size_t bytes, void* destination);
    // download() in two halves, so that the host can enqueue more work before it waits: startRead enqueues
    // the read, finishRead waits for it and for the kernels enqueued before it (not those enqueued since).
    // `destination` must stay valid until finishRead, or waitForQueue when a caller gives up.
    struct PendingRead {
        cl::Event event;
        std::uint64_t kernelsBefore = 0; // run() calls before the read
        std::size_t bytes = 0;
    };
    PendingRead startRead(const cl::Buffer& buffer, std::size_t bytes, void* destination);
    void finishRead(const PendingRead& read);
    // Waits until every command enqueued so far has ended, whatever its outcome (for an owner of host memory
    // a queued command may still use, before it frees it on an error path); throws nothing.
    void waitForQueue() noexcept;

    // Enqueues a kernel over an NDRange without waiting for it: the queue is in order, so a later kernel
    // or read sees its output. The next download (or takeTimings) waits for it, records its device time
    // and throws ibl::Error naming it if it failed. One wait per read instead of one per kernel: a small
    // LD level is two kernels of ~0.1 ms, where each wait cost about as much again on PoCL.
    void run(cl::Kernel& kernel, const cl::NDRange& global, const cl::NDRange& local = cl::NullRange);

    std::vector<DispatchTiming> takeTimings();

  private:
    Context(cl::Device device, DeviceInfo info);

    cl::Device device_;
    DeviceInfo info_;
    std::string baseOptions_;
    cl::Context context_;
    cl::CommandQueue queue_;
    mutable std::mutex mutex_;
    std::map<std::string, cl::Program> programs_;
    std::vector<std::filesystem::path> binaryDirectories_;
    // By binary key, with the directories that lack it (every one for a binary built from source).
    struct UnstoredBinary {
        std::vector<unsigned char> binary;
        std::vector<std::filesystem::path> directories;
    };
    std::map<std::string, UnstoredBinary> unstoredBinaries_;
    ProgramBuilds builds_;
    std::function<void(const std::string&, double)> compileObserver_;
    double compiledBytes_ = 0.0, compileSeconds_ = 0.0; // of the builds from source so far
    std::vector<DispatchTiming> timings_;
    struct PendingDispatch {
        std::string kernel;
        cl::Event event;
        std::uint64_t sequence; // its run() call's number
    };
    std::vector<PendingDispatch> pending_; // kernels enqueued and not yet waited for, in order
    std::uint64_t kernelsRun_ = 0;

    // Waits for the pending kernels run before kernel number `before` and `last` (a read after them, if any)
    // and records those kernels' times. Throws ibl::Error naming the first kernel that failed, else
    // `failure(last's error)`.
    void waitForPending(std::uint64_t before, const cl::Event* last,
                        const std::function<std::string(const cl::Error&)>& failure);
};

} // namespace ibl::ocl
