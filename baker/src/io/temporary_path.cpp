#include "iblbake/core/temporary_path.h"

#include <atomic>
#include <random>
#include <string>
#include <unistd.h>

namespace ibl {

std::filesystem::path temporaryPathBeside(const std::filesystem::path& target) {
    static std::atomic<unsigned long long> counter{0};
    thread_local std::mt19937_64 random{std::random_device{}()};
    std::string name = "."; // built by appending: GCC 12 warns (-Wrestrict) on "." + std::string&&
    name += target.stem().string();
    name += ".tmp-" + std::to_string(::getpid()) + "-" + std::to_string(counter++) + "-" +
            std::to_string(random() & 0xffffffu) + target.extension().string();
    return target.parent_path() / name;
}

} // namespace ibl
