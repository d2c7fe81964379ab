// Writes that never leave a partial file: write to a temporary name beside the target, then rename.
// A target the user already had is replaced only by a complete new file, and kept when writing fails.
#pragma once

#include <filesystem>
#include <initializer_list>
#include <string>
#include <string_view>

namespace ibl {

// Throws ibl::OutputError naming `target` when its directory does not exist or is not writable, or when it
// is a directory: what AtomicFile checks, for a command to check every output before any work.
void checkOutputFile(const std::filesystem::path& target);

// The extension of `file` in lower case (".dds" for "Chain.DDS").
std::string lowercaseExtension(const std::filesystem::path& file);

// Throws ibl::OutputError "<target>: written as <container> (<extension>), not <its extension>" unless
// `target` ends in `extension` (any case): a writer makes one container (.ktx2 KTX2, .exr OpenEXR, .json
// JSON, .png PNG), and a file named for another would hold bytes its name does not say (a .dds holding KTX2).
void checkOutputExtension(const std::filesystem::path& target, std::string_view extension);
// The same with several containers: "written as KTX2 (.ktx2) or DDS (.dds), not .exr".
void checkOutputExtension(const std::filesystem::path& target,
                          std::initializer_list<std::string_view> extensions);
// A cube product (LD chain, rough layers, irradiance cube) is delivered as KTX2 (.ktx2) or DDS (.dds), by the
// name's extension (iblbake/ktx2/dds.h).
void checkCubeOutputExtension(const std::filesystem::path& target);

class AtomicFile {
  public:
    // Throws ibl::Error naming `target` when its directory does not exist or is not writable.
    explicit AtomicFile(std::filesystem::path target);
    ~AtomicFile(); // removes the temporary file unless commit() succeeded
    AtomicFile(const AtomicFile&) = delete;
    AtomicFile& operator=(const AtomicFile&) = delete;

    // Where to write: same directory and extension as the target, so writers pick the same format.
    const std::filesystem::path& tempPath() const { return temp_; }
    const std::filesystem::path& target() const { return target_; }
    void commit(); // atomic rename onto the target

  private:
    std::filesystem::path target_;
    std::filesystem::path temp_;
    bool committed_ = false;
};

// Writes `bytes` to `file` (created or truncated) and flushes them to disk. Throws ibl::OutputError
// "<file>: cannot write: <the system's reason>" ("No space left on device", "Read-only file system"), naming
// `name` when given (the target of a temporary file) instead of the file.
void writeFileBytes(const std::filesystem::path& file, std::string_view bytes, const std::string& name = "");

} // namespace ibl
