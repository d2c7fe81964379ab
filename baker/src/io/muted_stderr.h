// Mutes the process's stderr for a scope. libpng (inside OpenImageIO) prints its own diagnostics
// straight to stderr; the same message comes back through OIIO's geterror(), which our one-line error
// reports, so stderr is muted while a file is decoded. Nothing of ours writes to stderr meanwhile.
#pragma once

#include <cstdio>
#include <fcntl.h>
#include <unistd.h>

namespace ibl {

class MutedStderr {
  public:
    MutedStderr() {
        std::fflush(stderr);
        saved_ = ::dup(STDERR_FILENO);
        int devNull = ::open("/dev/null", O_WRONLY);
        if (devNull >= 0) {
            ::dup2(devNull, STDERR_FILENO);
            ::close(devNull);
        }
    }
    ~MutedStderr() {
        std::fflush(stderr);
        if (saved_ >= 0) {
            ::dup2(saved_, STDERR_FILENO);
            ::close(saved_);
        }
    }
    MutedStderr(const MutedStderr&) = delete;
    MutedStderr& operator=(const MutedStderr&) = delete;

  private:
    int saved_ = -1;
};

} // namespace ibl
