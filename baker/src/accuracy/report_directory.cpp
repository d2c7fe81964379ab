// writeAccuracyReports (iblbake/accuracy/accuracy.h): the three reports appear together or not at all.
#include "iblbake/accuracy/accuracy.h"
#include "iblbake/core/error.h"
#include "iblbake/ktx2/atomic_file.h"

#include <unistd.h>

namespace ibl {

namespace {

namespace fs = std::filesystem;

void writeText(const fs::path& file, const std::string& text) {
    writeFileBytes(file, text);
}

} // namespace

void writeAccuracyReports(const fs::path& directory, const AccuracyRun& run) {
    const fs::path target = fs::absolute(directory);
    fs::create_directories(target.parent_path());
    const fs::path temp =
        target.parent_path() / (target.filename().string() + ".tmp-" + std::to_string(getpid()));
    fs::remove_all(temp);
    fs::create_directory(temp);
    try {
        writeText(temp / "report.json", accuracyJson(run));
        writeText(temp / "report.md", accuracyMarkdown(run));
        writeText(temp / "report.html", accuracyHtml(run));
        if (!fs::exists(target)) {
            fs::rename(temp, target);
            return;
        }
        for (const char* name : {"report.json", "report.md", "report.html"})
            fs::rename(temp / name, target / name);
        fs::remove(temp);
    } catch (...) {
        std::error_code ignored;
        fs::remove_all(temp, ignored);
        throw;
    }
}

} // namespace ibl
