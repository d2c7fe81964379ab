#include "program_binaries.h"
#include "iblbake/core/temporary_path.h"
#include "iblbake/opencl/opencl_context.h"

#include <xxhash.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>

namespace ibl::ocl {

namespace fs = std::filesystem;

namespace {

// File layout: magic, the key (32 hex digits), the payload's XXH3-128 (32 hex digits), the payload.
constexpr char kMagic[8] = {'I', 'B', 'L', 'C', 'L', 'B', '1', '\n'};
constexpr std::size_t kHexDigits = 32;
constexpr std::size_t kHeaderBytes = sizeof kMagic + 2 * kHexDigits;
// PoCL's binaries of our largest program are a few MB; anything far larger is not ours.
constexpr std::uintmax_t kMaxBinaryBytes = 256u << 20;

std::string hex(XXH128_hash_t h) {
    char text[kHexDigits + 1];
    std::snprintf(text, sizeof text, "%016llx%016llx", (unsigned long long)h.high64,
                  (unsigned long long)h.low64);
    return text;
}

std::string payloadHash(const ProgramBinary& payload) {
    return hex(XXH3_128bits(payload.data(), payload.size()));
}

fs::path fileFor(const fs::path& directory, const std::string& key) {
    return directory / (key + ".clbin");
}

} // namespace

std::string programBinaryKey(const cl::Device& device, const std::string& options,
                             const std::string& source) {
    const cl::Platform platform(device.getInfo<CL_DEVICE_PLATFORM>());
    XXH3_state_t* state = XXH3_createState();
    XXH3_128bits_reset(state);
    // Each field with its length first, so that no two field lists give the same byte stream.
    for (const std::string& field :
         {platform.getInfo<CL_PLATFORM_NAME>(), platform.getInfo<CL_PLATFORM_VERSION>(),
          device.getInfo<CL_DEVICE_NAME>(), device.getInfo<CL_DEVICE_VERSION>(),
          device.getInfo<CL_DRIVER_VERSION>(), options, source}) {
        const std::uint64_t size = field.size();
        XXH3_128bits_update(state, &size, sizeof size);
        XXH3_128bits_update(state, field.data(), field.size());
    }
    const std::string key = hex(XXH3_128bits_digest(state));
    XXH3_freeState(state);
    return key;
}

std::optional<ProgramBinary> readProgramBinary(const fs::path& directory, const std::string& key) {
    const fs::path file = fileFor(directory, key);
    std::error_code ec;
    const std::uintmax_t size = fs::file_size(file, ec);
    if (ec || !fs::is_regular_file(file, ec) || size <= kHeaderBytes || size > kMaxBinaryBytes)
        return std::nullopt;
    std::ifstream in(file, std::ios::binary);
    std::string header(kHeaderBytes, '\0');
    if (!in.read(header.data(), std::streamsize(header.size()))) return std::nullopt;
    if (std::memcmp(header.data(), kMagic, sizeof kMagic) != 0 ||
        header.compare(sizeof kMagic, kHexDigits, key) != 0)
        return std::nullopt;
    ProgramBinary payload(std::size_t(size - kHeaderBytes));
    if (!in.read(reinterpret_cast<char*>(payload.data()), std::streamsize(payload.size())))
        return std::nullopt;
    if (header.compare(sizeof kMagic + kHexDigits, kHexDigits, payloadHash(payload)) != 0)
        return std::nullopt;
    return payload;
}

bool writeProgramBinary(const fs::path& directory, const std::string& key, const ProgramBinary& binary) {
    std::error_code ec;
    fs::create_directories(directory, ec);
    const fs::path target = fileFor(directory, key);
    const fs::path temporary = temporaryPathBeside(target);
    {
        std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
        out.write(kMagic, sizeof kMagic);
        out << key << payloadHash(binary);
        out.write(reinterpret_cast<const char*>(binary.data()), std::streamsize(binary.size()));
        out.close();
        if (!out) {
            fs::remove(temporary, ec);
            return false;
        }
    }
    fs::rename(temporary, target, ec);
    if (!ec) return true;
    fs::remove(temporary, ec);
    return false;
}

std::optional<fs::path> userProgramBinaryDirectory() {
    if (const char* chosen = std::getenv("IBLBAKE_KERNEL_CACHE"))
        return *chosen ? std::optional<fs::path>(chosen) : std::nullopt;
    auto absolute = [](const char* variable) -> std::optional<fs::path> {
        const char* value = std::getenv(variable);
        if (!value || !fs::path(value).is_absolute()) return std::nullopt;
        return fs::path(value);
    };
    if (std::optional<fs::path> cache = absolute("XDG_CACHE_HOME")) return *cache / "iblbake" / "kernels";
    if (std::optional<fs::path> home = absolute("HOME")) return *home / ".cache" / "iblbake" / "kernels";
    return std::nullopt;
}

} // namespace ibl::ocl
