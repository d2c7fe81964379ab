#include "iblbake/ktx2/atomic_file.h"
#include "iblbake/core/error.h"
#include "iblbake/core/temporary_path.h"

#include <cctype>
#include <cerrno>
#include <cstring>
#include <fcntl.h>
#include <map>
#include <unistd.h>

namespace ibl {

namespace fs = std::filesystem;

void checkOutputFile(const fs::path& target) {
    const fs::path dir = target.parent_path().empty() ? fs::path(".") : target.parent_path();
    std::error_code ec;
    if (!fs::is_directory(dir, ec))
        throw OutputError(target.string() + ": directory " + dir.string() + " does not exist");
    if (::access(dir.c_str(), W_OK) != 0)
        throw OutputError(target.string() + ": cannot write to directory " + dir.string() + ": " +
                          std::strerror(errno));
    if (fs::is_directory(target, ec)) throw OutputError(target.string() + ": is a directory");
}

std::string lowercaseExtension(const fs::path& file) {
    std::string extension = file.extension().string();
    for (char& c : extension)
        c = char(std::tolower(static_cast<unsigned char>(c)));
    return extension;
}

void checkOutputExtension(const fs::path& target, std::initializer_list<std::string_view> extensions) {
    const std::string got = lowercaseExtension(target);
    static const std::map<std::string_view, std::string_view> containers = {
        {".ktx2", "KTX2"}, {".dds", "DDS"}, {".exr", "OpenEXR"}, {".json", "JSON"}, {".png", "PNG"}};
    std::string named;
    for (std::string_view extension : extensions) {
        if (got == extension) return;
        named += std::string(named.empty() ? "" : " or ") + std::string(containers.at(extension)) + " (" +
                 std::string(extension) + ")";
    }
    throw OutputError(target.string() + ": written as " + named + ", not " +
                      (got.empty() ? "a name without an extension" : got));
}

void checkOutputExtension(const fs::path& target, std::string_view extension) {
    checkOutputExtension(target, {extension});
}

void checkCubeOutputExtension(const fs::path& target) {
    checkOutputExtension(target, {".ktx2", ".dds"});
}

AtomicFile::AtomicFile(fs::path target) : target_(std::move(target)) {
    checkOutputFile(target_);
    temp_ = temporaryPathBeside(target_);
}

AtomicFile::~AtomicFile() {
    if (!committed_) {
        std::error_code ec;
        fs::remove(temp_, ec);
    }
}

void AtomicFile::commit() {
    std::error_code ec;
    fs::rename(temp_, target_, ec);
    if (ec)
        throw OutputError(target_.string() + ": cannot move the finished file into place: " + ec.message());
    committed_ = true;
}

void writeFileBytes(const fs::path& file, std::string_view bytes, const std::string& name) {
    const std::string shown = name.empty() ? file.string() : name;
    auto fail = [&](const char* what) {
        throw OutputError(shown + ": " + what + ": " + std::strerror(errno));
    };
    const int fd = ::open(file.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    if (fd < 0) fail("cannot create");
    const char* p = bytes.data();
    std::size_t left = bytes.size();
    while (left > 0) {
        const ssize_t n = ::write(fd, p, left);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) {
            const int error = n < 0 ? errno : ENOSPC; // a write of 0 bytes: the device is full
            ::close(fd);
            errno = error;
            fail("cannot write");
        }
        p += n;
        left -= std::size_t(n);
    }
    // A full disk may show only here (delayed allocation, network file systems).
    if (::fsync(fd) != 0) {
        const int error = errno;
        ::close(fd);
        errno = error;
        fail("cannot write");
    }
    if (::close(fd) != 0) fail("cannot write");
}

} // namespace ibl
