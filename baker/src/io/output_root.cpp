// The output root (iblbake/core/output_root.h): a directory descriptor of the root, and directories below it
// opened with O_NOFOLLOW one component at a time (openat(2)); their /proc/self/fd paths name the opened
// directory itself, so every later path below them is resolved from it and not from the text of the path.
#include "iblbake/core/output_root.h"
#include "iblbake/core/error.h"

#include <cerrno>
#include <cstring>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

namespace ibl {

namespace fs = std::filesystem;

namespace {

// Whether `path` is `root` or below it, both absolute and normalized.
bool isBelow(const fs::path& path, const fs::path& root) {
    auto p = path.begin();
    for (auto r = root.begin(); r != root.end(); ++r, ++p)
        if (r->empty())
            break; // a trailing separator
        else if (p == path.end() || *p != *r)
            return false;
    return true;
}

} // namespace

OutputRoot::OutputRoot(const fs::path& root) {
    std::error_code ec;
    path_ = fs::canonical(root, ec);
    if (ec) throw Error(root.string() + ": output root: " + ec.message());
    rootDescriptor_ = ::open(path_.c_str(), O_PATH | O_DIRECTORY | O_CLOEXEC);
    if (rootDescriptor_ < 0) throw Error(root.string() + ": output root: " + std::strerror(errno));
}

OutputRoot::~OutputRoot() {
    for (int fd : openDirectories_)
        ::close(fd);
    if (rootDescriptor_ >= 0) ::close(rootDescriptor_);
}

fs::path OutputRoot::below(const fs::path& target) const {
    std::error_code ec;
    const fs::path resolved = fs::weakly_canonical(fs::absolute(target), ec);
    if (ec) throw OutputError(target.string() + ": " + ec.message());
    if (!isBelow(resolved, path_)) {
        const fs::path lexical = fs::absolute(target).lexically_normal();
        throw OutputError(target.string() + " is outside the output root " + path_.string() +
                          (isBelow(lexical, path_) ? " (it leads to " + resolved.string() + ")" : ""));
    }
    return resolved.lexically_relative(path_);
}

fs::path OutputRoot::openDirectory(const fs::path& relative, std::vector<fs::path>& created) {
    int current = rootDescriptor_;
    fs::path reached = path_;
    for (const fs::path& component : relative) {
        if (component.empty() || component == ".") continue;
        if (component == "..") throw OutputError((path_ / relative).string() + ": leaves the output root");
        reached /= component;
        const bool made = ::mkdirat(current, component.c_str(), 0777) == 0;
        if (!made && errno != EEXIST)
            throw OutputError(reached.string() + ": cannot create it: " + std::strerror(errno));
        if (made) created.push_back(reached);
        const int next = ::openat(current, component.c_str(), O_PATH | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
        if (next < 0) {
            struct stat status {};
            const bool link = ::fstatat(current, component.c_str(), &status, AT_SYMLINK_NOFOLLOW) == 0 &&
                              S_ISLNK(status.st_mode);
            throw OutputError(reached.string() + ": " +
                              (link ? "is a symbolic link (refused below an output root)"
                                    : std::string("cannot open it: ") + std::strerror(errno)));
        }
        openDirectories_.push_back(next);
        current = next;
    }
    return fs::path("/proc/self/fd") / std::to_string(current);
}

} // namespace ibl
