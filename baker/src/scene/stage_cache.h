// The stage cache (docs/scenes.md "Cache"): one directory per entry, named by the stage's key, holding its
// files and entry.json with each file's content hash. Entries are written into a private staging directory
// and renamed into place (atomic on one file system, local or shared), so concurrent runs never see a torn
// entry; an entry whose files do not match their recorded hashes is removed and recomputed.
#pragma once

#include <filesystem>
#include <optional>
#include <string>

namespace ibl {

// One stage's files before they become a cache entry: a new directory beside the entries, locked (flock
// on its owner file) while this object lives, so that a later run can tell a dead run's leftovers from a
// live run's work. Removed on destruction unless committed.
class StagedEntry {
  public:
    StagedEntry(std::string key, std::filesystem::path directory, int ownerLock);
    StagedEntry(StagedEntry&& other) noexcept;
    StagedEntry& operator=(StagedEntry&&) = delete;
    StagedEntry(const StagedEntry&) = delete;
    ~StagedEntry();

    const std::string& key() const { return key_; }
    const std::filesystem::path& directory() const { return directory_; }

  private:
    friend class StageCache;
    std::string key_;
    std::filesystem::path directory_;
    int ownerLock_ = -1;
    bool committed_ = false;
};

class StageCache {
  public:
    // Created when missing (throws ibl::OutputError naming it and the reason). Removes what runs that no
    // longer live left behind: staging directories whose owner lock is free, and trash.
    explicit StageCache(std::filesystem::path directory);

    // The entry's directory when it exists and is intact; a damaged entry is removed (nullopt).
    std::optional<std::filesystem::path> find(const std::string& key) const;
    StagedEntry staging(const std::string& key) const;
    // Hashes the staged files into entry.json: the last write of an entry, so that committing it is one
    // rename that cannot run out of space.
    void seal(const StagedEntry& staged) const;
    // Renames a sealed entry to its key. When another run committed the same key first, its entry is kept
    // and the staging directory removed.
    std::filesystem::path commit(StagedEntry& staged) const;

    const std::filesystem::path& directory() const { return directory_; }

  private:
    void removeStaleStaging() const;
    std::filesystem::path directory_;
};

// A name no other process or thread on any machine will pick: pid, a per-process counter and 64 random bits.
std::string uniqueSuffix();

// Copies a product from its cache entry to `temporary`, the file an OutputSet writes beside its target: a
// failure (a full disk) throws ibl::OutputError naming `temporary` (which the set replaces with the target)
// and the system's reason.
void copyProductFile(const std::filesystem::path& from, const std::filesystem::path& temporary);

} // namespace ibl
