// OutputSet and the temporary-name rule (iblbake/ktx2/output_set.h, iblbake/core/temporary_path.h): the
// mechanism behind docs/scenes.md "Failures leave nothing behind", tested on its own.
#include "cli_runner.h"
#include "test_support.h"

#include <iblbake/core/error.h>
#include <iblbake/core/temporary_path.h>
#include <iblbake/ktx2/atomic_file.h>
#include <iblbake/ktx2/output_set.h>

#include <fstream>
#include <set>

namespace fs = std::filesystem;

namespace {

std::set<std::string> listing(const fs::path& dir) {
    std::set<std::string> names;
    for (const auto& e : fs::recursive_directory_iterator(dir))
        names.insert(fs::relative(e.path(), dir).string());
    return names;
}

// Hidden, beside the target, the target's extension kept (writers choose formats by it), and never the
// same name twice.
TEST(TemporaryPath, HiddenBesideTheTargetWithItsExtensionAndUnique) {
    std::set<fs::path> seen;
    for (int i = 0; i < 1000; ++i) {
        const fs::path temporary = ibl::temporaryPathBeside("out/dir/sky_ld.ktx2");
        EXPECT_EQ(temporary.parent_path(), fs::path("out/dir"));
        EXPECT_EQ(temporary.extension(), ".ktx2");
        EXPECT_EQ(temporary.filename().string().rfind(".sky_ld.tmp-", 0), 0u) << temporary;
        EXPECT_TRUE(seen.insert(temporary).second) << temporary;
    }
    EXPECT_EQ(ibl::temporaryPathBeside("report").parent_path(), fs::path());
}

// A write that fails with a SettingError keeps its type and setting (the CLI names its flag, a scene bake
// its key) and names the target, never the temporary; the set then leaves nothing, not even the directories
// it created.
TEST(OutputSet, AFailedWriteKeepsItsErrorAndLeavesNothing) {
    const fs::path dir = ibl::test::freshTempDir("output_set_fail");
    {
        ibl::OutputSet outputs;
        outputs.createDirectories(dir / "a" / "b", "products");
        outputs.writeFile(dir / "a" / "b" / "first.json",
                          [](const fs::path& t) { ibl::writeFileBytes(t, "{}"); });
        try {
            outputs.writeFile(dir / "a" / "b" / "second.ktx2", [](const fs::path& temporary) {
                throw ibl::SettingError("layout", temporary.string() + ": unknown layout");
            });
            FAIL() << "no error";
        } catch (const ibl::SettingError& e) {
            EXPECT_EQ(e.setting(), "layout");
            EXPECT_EQ(std::string(e.what()), (dir / "a" / "b" / "second.ktx2").string() + ": unknown layout");
        }
    }
    EXPECT_TRUE(listing(dir).empty());
    fs::remove_all(dir);
}

// Committed, every file and directory is in place and no temporary is left; a directory output merges into
// an existing directory, keeping its other files.
TEST(OutputSet, ACommittedSetHasEveryOutputAndNoTemporary) {
    const fs::path dir = ibl::test::freshTempDir("output_set_commit");
    fs::create_directories(dir / "exr");
    std::ofstream(dir / "exr" / "notes.txt") << "kept";
    std::ofstream(dir / "exr" / "level_0.exr") << "old";
    {
        ibl::OutputSet outputs;
        outputs.writeFile(dir / "sky.ktx2", [](const fs::path& t) { ibl::writeFileBytes(t, "ktx"); });
        outputs.writeDirectory(dir / "exr",
                               [](const fs::path& t) { ibl::writeFileBytes(t / "level_0.exr", "new"); });
        outputs.commit();
    }
    EXPECT_EQ(listing(dir), (std::set<std::string>{"exr", "exr/level_0.exr", "exr/notes.txt", "sky.ktx2"}));
    std::ifstream in(dir / "exr" / "level_0.exr");
    EXPECT_EQ(std::string(std::istreambuf_iterator<char>(in), {}), "new");
    fs::remove_all(dir);
}

} // namespace
