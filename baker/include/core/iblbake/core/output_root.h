// An output root (`iblbake bake|batch --output-root DIR`, docs/scenes.md "Confined output"): on a farm that
// bakes scenes written by many people, everything a scene names for writing must lie below the root once
// symbolic links are resolved, and is reached from the root, at the time of writing, one real directory at a
// time without following links, so that a link placed or swapped in between cannot redirect a write.
#pragma once

#include <filesystem>
#include <vector>

namespace ibl {

class OutputRoot {
  public:
    // Opens `root` (which must be an existing directory; links in its own path are the operator's and are
    // followed). Throws ibl::Error "<root>: output root: <reason>".
    explicit OutputRoot(const std::filesystem::path& root);
    OutputRoot(const OutputRoot&) = delete;
    OutputRoot& operator=(const OutputRoot&) = delete;
    ~OutputRoot();

    // The root with its links resolved.
    const std::filesystem::path& path() const { return path_; }

    // `target` (relative to the working directory when not absolute) relative to the root, the links of its
    // existing part resolved and the rest normalized. Throws ibl::OutputError "<target> is outside the output
    // root <root>" (through links: "... (it leads to <resolved>)").
    std::filesystem::path below(const std::filesystem::path& target) const;

    // Opens the directory `relative` below the root (as below() returns it), walking from the root one
    // component at a time, each a real directory opened without following links, creating the missing ones
    // (each appended to `created` as root / ... once made). Returns "/proc/self/fd/N": a path that names
    // that very directory for as long as this OutputRoot lives, whatever links appear on the way later.
    // Throws ibl::OutputError "<root>/<relative>: <component> is a symbolic link (refused below an output
    // root)" or "...: cannot create it: <reason>".
    std::filesystem::path openDirectory(const std::filesystem::path& relative,
                                        std::vector<std::filesystem::path>& created);

  private:
    std::filesystem::path path_;
    int rootDescriptor_ = -1;
    std::vector<int> openDirectories_; // closed with the root
};

} // namespace ibl
