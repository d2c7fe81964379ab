// Input files a user names (HDRIs, scene files, batch manifests, the files a cache hashes): regular files
// only, after resolving symbolic links. A device (/dev/zero), a FIFO or a socket is refused in one line
// before anything reads it, so no hash, format probe or parser waits on endless or blocking input.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>

namespace ibl {

// An open regular file. Opened without blocking (a FIFO put in place of the file between the check and
// the open does not stall it), then refused by what fstat says it is. Throws ibl::Error "<file>: <cause>":
// "no such file", "Too many levels of symbolic links", "Permission denied" (the system's text), "is a
// directory", "is a character device, not a regular file", "is a FIFO, not a regular file", ...
class InputFile {
  public:
    explicit InputFile(const std::filesystem::path& file);
    ~InputFile();
    InputFile(const InputFile&) = delete;
    InputFile& operator=(const InputFile&) = delete;

    std::uint64_t size() const { return size_; }
    // Up to `bytes` bytes into `buffer`; 0 at the end. Throws ibl::Error "<file>: cannot read: <cause>".
    std::size_t read(char* buffer, std::size_t bytes);

  private:
    std::string name_;
    int fd_ = -1;
    std::uint64_t size_ = 0;
};

// Throws like InputFile unless `file` is a regular file (for readers that open files by name).
void requireRegularFile(const std::filesystem::path& file);

// The whole file, refused before it is read when it holds more than maxBytes: "<file>: is <n> bytes, more
// than the <maxBytes> bytes a <what> may have".
std::string readInputFile(const std::filesystem::path& file, std::uint64_t maxBytes, const std::string& what);

} // namespace ibl
