// Writes that never leave a partial file: write to a temporary name beside the target, then rename.
// A target the user already had is replaced only by a complete new file, and kept when writing fails.
#pragma once

#include <filesystem>

namespace ibl {

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

} // namespace ibl
