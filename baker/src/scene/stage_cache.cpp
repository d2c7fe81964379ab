#include "stage_cache.h"

#include "iblbake/bake_state/content_hash.h"
#include "iblbake/core/error.h"
#include "iblbake/ktx2/atomic_file.h"

#include <nlohmann/json.hpp>

#include <atomic>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <fcntl.h>
#include <fstream>
#include <random>
#include <sys/file.h>
#include <unistd.h>

namespace ibl {

namespace fs = std::filesystem;

namespace {

constexpr const char* kEntryFile = "entry.json";
constexpr const char* kOwnerFile = ".owner";
constexpr const char* kStagingPrefix = ".staging-";
constexpr const char* kTrashPrefix = ".trash-";
// A staging directory without an owner file exists only between its mkdir and the owner's creation, and
// between the owner's removal and the commit's rename; one that stays so for this long was left by a run
// killed in that instant (or by a version without owner files).
constexpr auto kOwnerlessStagingAge = std::chrono::hours(1);

// Moves a directory out of the way first (one rename, atomic), then deletes it: a concurrent reader sees
// either the whole entry or none.
void removeDirectory(const fs::path& dir) {
    std::error_code ec;
    const fs::path trash = dir.parent_path() / (kTrashPrefix + uniqueSuffix());
    fs::rename(dir, trash, ec);
    fs::remove_all(ec ? dir : trash, ec);
}

bool intact(const fs::path& dir) {
    try {
        std::ifstream in(dir / kEntryFile);
        if (!in) return false;
        const nlohmann::json entry = nlohmann::json::parse(in);
        for (const auto& [name, hash] : entry.at("files").items())
            if (hashFile(dir / name) != hash.get<std::string>()) return false;
        return true;
    } catch (const std::exception&) { // unreadable, malformed or missing: not a usable entry
        return false;
    }
}

} // namespace

std::string uniqueSuffix() {
    static std::atomic<unsigned long long> counter{0};
    thread_local std::mt19937_64 random{std::random_device{}()};
    return std::to_string(::getpid()) + "-" + std::to_string(counter++) + "-" + std::to_string(random());
}

void copyProductFile(const fs::path& from, const fs::path& temporary) {
    std::error_code ec;
    fs::copy_file(from, temporary, fs::copy_options::overwrite_existing, ec);
    if (ec) throw OutputError(temporary.string() + ": cannot write: " + ec.message());
}

StagedEntry::StagedEntry(std::string key, fs::path directory, int ownerLock)
    : key_(std::move(key)), directory_(std::move(directory)), ownerLock_(ownerLock) {}

StagedEntry::StagedEntry(StagedEntry&& other) noexcept
    : key_(std::move(other.key_)), directory_(std::move(other.directory_)), ownerLock_(other.ownerLock_),
      committed_(other.committed_) {
    other.ownerLock_ = -1;
    other.committed_ = true; // the moved-from object owns nothing
}

StagedEntry::~StagedEntry() {
    if (!committed_) {
        std::error_code ec;
        fs::remove_all(directory_, ec);
    }
    if (ownerLock_ >= 0) ::close(ownerLock_); // releases the lock, after the directory is gone
}

StageCache::StageCache(fs::path directory) : directory_(std::move(directory)) {
    std::error_code ec;
    fs::create_directories(directory_, ec);
    if (ec || !fs::is_directory(directory_))
        throw OutputError(directory_.string() + ": cannot create the cache directory" +
                          (ec ? ": " + ec.message() : std::string()));
    removeStaleStaging();
}

// flock is released by the kernel when its process ends, however it ends (SIGKILL included), so a free lock
// means a dead owner; on NFS, Linux maps flock to byte-range locks that every client sees.
void StageCache::removeStaleStaging() const {
    std::error_code ec;
    for (fs::directory_iterator it(directory_, ec), end; !ec && it != end; it.increment(ec)) {
        const std::string name = it->path().filename().string();
        if (name.starts_with(kTrashPrefix)) { // only its remover uses it, and removing twice is harmless
            fs::remove_all(it->path(), ec);
            ec.clear();
            continue;
        }
        if (!name.starts_with(kStagingPrefix) || !it->is_directory(ec)) continue;
        const int owner = ::open((it->path() / kOwnerFile).c_str(), O_RDONLY | O_CLOEXEC | O_NOFOLLOW);
        if (owner < 0) {
            const bool ownerless = errno == ENOENT;
            const auto age = fs::file_time_type::clock::now() - fs::last_write_time(it->path(), ec);
            if (!ec && ownerless && age > kOwnerlessStagingAge) removeDirectory(it->path());
            ec.clear();
            continue;
        }
        if (::flock(owner, LOCK_EX | LOCK_NB) == 0) removeDirectory(it->path());
        ::close(owner);
    }
}

std::optional<fs::path> StageCache::find(const std::string& key) const {
    const fs::path dir = directory_ / key;
    std::error_code ec;
    if (!fs::is_directory(dir, ec)) return std::nullopt;
    if (intact(dir)) return dir;
    removeDirectory(dir);
    return std::nullopt;
}

StagedEntry StageCache::staging(const std::string& key) const {
    const fs::path dir = directory_ / (kStagingPrefix + key + "-" + uniqueSuffix());
    std::error_code ec;
    if (!fs::create_directory(dir, ec))
        throw OutputError(dir.string() + ": cannot create a cache staging directory: " + ec.message());
    const int owner = ::open((dir / kOwnerFile).c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
    if (owner < 0 || ::flock(owner, LOCK_EX | LOCK_NB) != 0) {
        const std::string reason = std::strerror(errno);
        if (owner >= 0) ::close(owner);
        fs::remove_all(dir, ec);
        throw OutputError(dir.string() + ": cannot lock a cache staging directory: " + reason);
    }
    return StagedEntry(key, dir, owner);
}

void StageCache::seal(const StagedEntry& staged) const {
    nlohmann::json files = nlohmann::json::object();
    for (const fs::directory_entry& e : fs::directory_iterator(staged.directory()))
        if (e.is_regular_file() && e.path().filename() != kOwnerFile)
            files[e.path().filename().string()] = hashFile(e.path());
    writeFileBytes(staged.directory() / kEntryFile,
                   nlohmann::json{{"key", staged.key()}, {"files", files}}.dump(2) + '\n');
}

fs::path StageCache::commit(StagedEntry& staged) const {
    const fs::path target = directory_ / staged.key();
    // The lock stays held (the descriptor is open) while the owner file is gone: a cleaner that opened it
    // earlier cannot take the lock, and one that comes later finds no owner file and a fresh directory.
    std::error_code ec;
    fs::remove(staged.directory() / kOwnerFile, ec);
    for (int attempt = 0; attempt < 2; ++attempt) {
        fs::rename(staged.directory(), target, ec);
        if (!ec) {
            staged.committed_ = true;
            return target;
        }
        if (find(staged.key())) return target; // another run committed the same key first: same content
    }
    throw OutputError(target.string() + ": cannot commit the cache entry: " + ec.message());
}

} // namespace ibl
