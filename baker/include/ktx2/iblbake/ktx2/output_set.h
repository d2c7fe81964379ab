// All outputs of one command, committed together (docs/scenes.md "Failures leave nothing behind"): each file
// is written under a temporary name beside its target and each output directory is built beside its target;
// commit() moves them all into place. An OutputSet destroyed without commit() removes every temporary
// and every directory it created, so a failed command leaves the tree as it was.
#pragma once

#include "iblbake/core/output_root.h"

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace ibl {

class OutputSet {
  public:
    OutputSet() = default;
    OutputSet(const OutputSet&) = delete;
    OutputSet& operator=(const OutputSet&) = delete;
    ~OutputSet();

    // Creates `directory` and its missing parents, keeping them only if the set is committed. Throws
    // ibl::OutputError "<what>: <directory>: cannot create it: <reason>".
    void createDirectories(const std::filesystem::path& directory, const std::string& what);

    // The same below an output root: `relative` (OutputRoot::below) opened from the root without following
    // links (OutputRoot::openDirectory), the directories it makes kept only if the set is committed. Returns
    // the path that names the opened directory (write below it). Throws ibl::OutputError "<what>: ...".
    std::filesystem::path createDirectoriesBelow(OutputRoot& root, const std::filesystem::path& relative,
                                                 const std::string& what);

    // Runs `write` on a temporary file beside `target` (same extension, so writers pick the same format);
    // an ibl::Error it throws is rethrown naming `target` instead of the temporary. The target is checked as
    // checkOutputFile does.
    void writeFile(const std::filesystem::path& target,
                   const std::function<void(const std::filesystem::path& temporary)>& write);
    // The same for a directory of files: `write` fills an empty temporary directory beside `target`; on
    // commit its files replace their namesakes in `target` (created when missing).
    void writeDirectory(const std::filesystem::path& target,
                        const std::function<void(const std::filesystem::path& temporary)>& write);

    // Moves every output into place, in the order they were written (so a manifest written last lands
    // last). Renames within a directory need no space, so once every output is written this cannot run
    // out of it.
    void commit();

  private:
    struct Staged {
        std::filesystem::path temporary, target;
        bool directory = false;
    };
    void run(const Staged& staged, const std::function<void(const std::filesystem::path&)>& write);

    std::vector<Staged> staged_;
    std::vector<std::filesystem::path> createdDirectories_; // parents first
    bool committed_ = false;
};

} // namespace ibl
