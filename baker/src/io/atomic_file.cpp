#include "iblbake/ktx2/atomic_file.h"
#include "iblbake/core/error.h"

#include <atomic>
#include <cerrno>
#include <cstring>
#include <unistd.h>

namespace ibl {

namespace fs = std::filesystem;

AtomicFile::AtomicFile(fs::path target) : target_(std::move(target)) {
    fs::path dir = target_.parent_path().empty() ? fs::path(".") : target_.parent_path();
    std::error_code ec;
    if (!fs::is_directory(dir, ec))
        throw Error(target_.string() + ": directory " + dir.string() + " does not exist");
    if (::access(dir.c_str(), W_OK) != 0)
        throw Error(target_.string() + ": cannot write to directory " + dir.string() + ": " +
                    std::strerror(errno));
    if (fs::is_directory(target_, ec)) throw Error(target_.string() + ": is a directory");
    static std::atomic<unsigned> counter{0};
    std::string name = "."; // built by appending: GCC 12 warns (-Wrestrict) on "." + std::string&&
    name += target_.stem().string();
    name +=
        ".tmp" + std::to_string(::getpid()) + "_" + std::to_string(counter++) + target_.extension().string();
    temp_ = dir / name;
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
    if (ec) throw Error(target_.string() + ": cannot move the finished file into place: " + ec.message());
    committed_ = true;
}

} // namespace ibl
