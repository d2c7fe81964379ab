#include "iblbake/ktx2/output_set.h"
#include "iblbake/core/error.h"
#include "iblbake/core/format_text.h"
#include "iblbake/core/temporary_path.h"
#include "iblbake/ktx2/atomic_file.h"

namespace ibl {

namespace fs = std::filesystem;

OutputSet::~OutputSet() {
    if (committed_) return;
    std::error_code ec;
    for (auto it = staged_.rbegin(); it != staged_.rend(); ++it)
        fs::remove_all(it->temporary, ec);
    for (auto it = createdDirectories_.rbegin(); it != createdDirectories_.rend(); ++it)
        fs::remove(*it, ec); // fails, as it should, on a directory something else has put a file in
}

void OutputSet::createDirectories(const fs::path& directory, const std::string& what) {
    std::vector<fs::path> missing;
    std::error_code ec;
    for (fs::path p = directory; !p.empty() && !fs::exists(fs::symlink_status(p, ec)); p = p.parent_path()) {
        missing.push_back(p);
        if (p == p.parent_path()) break;
    }
    for (auto it = missing.rbegin(); it != missing.rend(); ++it) {
        if (fs::create_directory(*it, ec))
            createdDirectories_.push_back(*it);
        else if (ec)
            throw OutputError(what + ": " + directory.string() + ": cannot create it: " + ec.message());
    }
    if (!fs::is_directory(directory, ec))
        throw OutputError(what + ": " + directory.string() + ": is not a directory");
}

fs::path OutputSet::createDirectoriesBelow(OutputRoot& root, const fs::path& relative,
                                           const std::string& what) {
    try {
        return root.openDirectory(relative, createdDirectories_);
    } catch (const OutputError& e) {
        throw OutputError(what + ": " + e.what());
    }
}

void OutputSet::run(const Staged& staged, const std::function<void(const fs::path&)>& write) {
    const std::string temporary = staged.temporary.string(), target = staged.target.string();
    try {
        write(staged.temporary);
    } catch (const OutputError& e) {
        throw OutputError(replaceAll(e.what(), temporary, target));
    } catch (const SettingError& e) { // keeps its setting, for the caller to name as a flag or scene key
        throw SettingError(e.setting(), replaceAll(e.what(), temporary, target));
    } catch (const Error& e) {
        throw Error(replaceAll(e.what(), temporary, target));
    }
}

void OutputSet::writeFile(const fs::path& target, const std::function<void(const fs::path&)>& write) {
    checkOutputFile(target);
    staged_.push_back({temporaryPathBeside(target), target, false});
    run(staged_.back(), write);
}

void OutputSet::writeDirectory(const fs::path& target, const std::function<void(const fs::path&)>& write) {
    std::error_code ec;
    if (fs::exists(target, ec) && !fs::is_directory(target, ec))
        throw OutputError(target.string() + ": is not a directory");
    const fs::path temporary = temporaryPathBeside(target);
    if (!fs::create_directory(temporary, ec))
        throw OutputError(target.string() + ": cannot create it: " + ec.message());
    staged_.push_back({temporary, target, true});
    run(staged_.back(), write);
}

void OutputSet::commit() {
    for (const Staged& s : staged_) {
        std::error_code ec;
        if (!s.directory || !fs::exists(s.target, ec)) {
            fs::rename(s.temporary, s.target, ec);
        } else {
            std::vector<fs::path> files; // listed first: renaming while iterating may skip entries
            for (const fs::directory_entry& e : fs::directory_iterator(s.temporary, ec))
                files.push_back(e.path());
            for (const fs::path& file : files) {
                fs::rename(file, s.target / file.filename(), ec);
                if (ec) break;
            }
            if (!ec) fs::remove(s.temporary, ec);
        }
        if (ec)
            throw OutputError(s.target.string() +
                              ": cannot move the finished output into place: " + ec.message());
    }
    committed_ = true;
}

} // namespace ibl
