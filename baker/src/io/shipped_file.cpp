#include "shipped_file.h"

#include <filesystem>
#include <system_error>

namespace ibl {

std::string shippedFile(const std::string& relativeToProgram, const std::string& buildTreePath) {
    namespace fs = std::filesystem;
    std::error_code ec;
    const fs::path program = fs::read_symlink("/proc/self/exe", ec);
    if (!ec) {
        const fs::path installed = (program.parent_path() / relativeToProgram).lexically_normal();
        if (fs::is_regular_file(installed, ec)) return installed.string();
    }
    return buildTreePath;
}

} // namespace ibl
