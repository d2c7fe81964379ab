#include "iblbake/core/input_file.h"

#include "iblbake/core/error.h"

#include <cerrno>
#include <cstring>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

namespace ibl {

namespace {

// What a file that is not a regular file is, for the refusal.
const char* kindOf(mode_t mode) {
    if (S_ISDIR(mode)) return "is a directory";
    if (S_ISCHR(mode)) return "is a character device, not a regular file";
    if (S_ISBLK(mode)) return "is a block device, not a regular file";
    if (S_ISFIFO(mode)) return "is a FIFO, not a regular file";
    if (S_ISSOCK(mode)) return "is a socket, not a regular file";
    return "is not a regular file";
}

} // namespace

InputFile::InputFile(const std::filesystem::path& file) : name_(printableForMessage(file.string())) {
    // O_NONBLOCK: opening a FIFO for reading would otherwise wait for a writer; O_NOCTTY: a terminal
    // named as input must not become ours.
    fd_ = ::open(file.c_str(), O_RDONLY | O_NONBLOCK | O_NOCTTY | O_CLOEXEC);
    if (fd_ < 0) {
        const int error = errno;
        throw Error(name_ + ": " + (error == ENOENT ? std::string("no such file") : std::strerror(error)));
    }
    struct stat status {};
    const char* why = ::fstat(fd_, &status) != 0 ? std::strerror(errno)
                      : S_ISREG(status.st_mode)  ? nullptr
                                                 : kindOf(status.st_mode);
    if (why) {
        ::close(fd_);
        throw Error(name_ + ": " + why);
    }
    size_ = std::uint64_t(status.st_size);
}

InputFile::~InputFile() {
    ::close(fd_);
}

std::size_t InputFile::read(char* buffer, std::size_t bytes) {
    for (;;) {
        const ssize_t n = ::read(fd_, buffer, bytes);
        if (n >= 0) return std::size_t(n);
        if (errno != EINTR) throw Error(name_ + ": cannot read: " + std::strerror(errno));
    }
}

void requireRegularFile(const std::filesystem::path& file) {
    InputFile open(file);
}

std::string readInputFile(const std::filesystem::path& file, std::uint64_t maxBytes,
                          const std::string& what) {
    InputFile in(file);
    if (in.size() > maxBytes)
        throw Error(printableForMessage(file.string()) + ": is " + std::to_string(in.size()) +
                    " bytes, more than the " + std::to_string(maxBytes) + " bytes a " + what + " may have");
    std::string text(std::size_t(in.size()), '\0');
    std::size_t filled = 0;
    // A file that grows while it is read is cut at its size when opened (still within the limit).
    while (filled < text.size()) {
        const std::size_t n = in.read(text.data() + filled, text.size() - filled);
        if (n == 0) break;
        filled += n;
    }
    text.resize(filled);
    return text;
}

} // namespace ibl
