#include "stage_cache.h"

#include "iblbake/bake_state/content_hash.h"
#include "iblbake/core/error.h"
#include "iblbake/ktx2/atomic_file.h"

#include <nlohmann/json.hpp>

#include <atomic>
#include <fstream>
#include <random>
#include <unistd.h>

namespace ibl {

namespace fs = std::filesystem;

namespace {

constexpr const char* kEntryFile = "entry.json";

// Moves a directory out of the way first (one rename, atomic), then deletes it: a concurrent reader sees
// either the whole entry or none.
void removeDirectory(const fs::path& dir) {
    std::error_code ec;
    const fs::path trash = dir.parent_path() / (".trash-" + uniqueSuffix());
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

StageCache::StageCache(fs::path directory) : directory_(std::move(directory)) {
    std::error_code ec;
    fs::create_directories(directory_, ec);
    if (ec || !fs::is_directory(directory_))
        throw OutputError(directory_.string() + ": cannot create the cache directory" +
                          (ec ? ": " + ec.message() : std::string()));
}

std::optional<fs::path> StageCache::find(const std::string& key) const {
    const fs::path dir = directory_ / key;
    std::error_code ec;
    if (!fs::is_directory(dir, ec)) return std::nullopt;
    if (intact(dir)) return dir;
    removeDirectory(dir);
    return std::nullopt;
}

fs::path StageCache::staging(const std::string& key) const {
    const fs::path dir = directory_ / (".staging-" + key + "-" + uniqueSuffix());
    std::error_code ec;
    if (!fs::create_directory(dir, ec))
        throw OutputError(dir.string() + ": cannot create a cache staging directory: " + ec.message());
    return dir;
}

fs::path StageCache::commit(const std::string& key, const fs::path& staging) const {
    nlohmann::json files = nlohmann::json::object();
    for (const fs::directory_entry& e : fs::directory_iterator(staging))
        if (e.is_regular_file()) files[e.path().filename().string()] = hashFile(e.path());
    writeFileBytes(staging / kEntryFile, nlohmann::json{{"key", key}, {"files", files}}.dump(2) + '\n');
    const fs::path target = directory_ / key;
    for (int attempt = 0; attempt < 2; ++attempt) {
        std::error_code ec;
        fs::rename(staging, target, ec);
        if (!ec) return target;
        if (find(key)) { // another run committed the same key first: same inputs, same content
            discard(staging);
            return target;
        }
    }
    discard(staging);
    throw Error(target.string() + ": cannot commit the cache entry");
}

void StageCache::discard(const fs::path& staging) const {
    std::error_code ec;
    fs::remove_all(staging, ec);
}

void copyAtomically(const fs::path& from, const fs::path& to) {
    std::string name = to.filename().string();
    name.insert(0, 1, '.');
    name += ".tmp-";
    name += uniqueSuffix();
    const fs::path temp = to.parent_path() / name;
    std::error_code ec;
    fs::copy_file(from, temp, fs::copy_options::overwrite_existing, ec);
    if (!ec) fs::rename(temp, to, ec);
    if (ec) {
        fs::remove(temp, ec);
        throw OutputError(to.string() + ": cannot write: " + ec.message());
    }
}

} // namespace ibl
