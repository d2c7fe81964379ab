// writeAccuracyReports (iblbake/accuracy/accuracy.h): the three reports appear together or not at all.
#include "iblbake/accuracy/accuracy.h"
#include "iblbake/ktx2/atomic_file.h"
#include "iblbake/ktx2/output_set.h"

namespace ibl {

void writeAccuracyReports(const std::filesystem::path& directory, const AccuracyRun& run) {
    OutputSet outputs;
    const std::filesystem::path target = std::filesystem::absolute(directory);
    outputs.createDirectories(target.parent_path(), "accuracy reports");
    outputs.writeDirectory(target, [&](const std::filesystem::path& temporary) {
        writeFileBytes(temporary / "report.json", accuracyJson(run));
        writeFileBytes(temporary / "report.md", accuracyMarkdown(run));
        writeFileBytes(temporary / "report.html", accuracyHtml(run));
    });
    outputs.commit();
}

} // namespace ibl
