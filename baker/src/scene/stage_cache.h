// The stage cache (README "Scenes"): one directory per entry, named by the stage's key, holding its files
// and entry.json with each file's content hash. Entries are written into a private staging directory and
// renamed into place (atomic on one file system, local or shared), so concurrent runs never see a torn
// entry; an entry whose files do not match their recorded hashes is removed and recomputed.
#pragma once

#include <filesystem>
#include <optional>
#include <string>

namespace ibl {

class StageCache {
  public:
    explicit StageCache(std::filesystem::path directory); // created when missing; throws ibl::Error

    // The entry's directory when it exists and is intact; a damaged entry is removed (nullopt).
    std::optional<std::filesystem::path> find(const std::string& key) const;
    // A new, empty directory beside the entries, unique to this call.
    std::filesystem::path staging(const std::string& key) const;
    // Hashes the staged files into entry.json and renames the directory to the key. When another run
    // committed the same key first, its entry is kept and the staging directory removed.
    std::filesystem::path commit(const std::string& key, const std::filesystem::path& staging) const;
    // Removes a staging directory left by a failed stage.
    void discard(const std::filesystem::path& staging) const;

    const std::filesystem::path& directory() const { return directory_; }

  private:
    std::filesystem::path directory_;
};

// A name no other process or thread on any machine will pick: pid, a per-process counter and 64 random bits.
std::string uniqueSuffix();

// Copies `from` to `to` through a temporary file beside `to` and a rename: readers see the old file or the
// new one, never part of one. Throws ibl::Error naming `to` on failure.
void copyAtomically(const std::filesystem::path& from, const std::filesystem::path& to);

} // namespace ibl
