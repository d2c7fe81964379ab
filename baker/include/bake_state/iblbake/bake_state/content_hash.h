// Content hashes for cache keys and the manifest: XXH3-128 (xxHash, Debian libxxhash-dev), written as 32
// lowercase hex digits. Stable across machines and runs: the same bytes give the same hash.
#pragma once

#include <filesystem>
#include <memory>
#include <string>
#include <string_view>

namespace ibl {

class ContentHasher {
  public:
    ContentHasher();
    ~ContentHasher();
    ContentHasher(const ContentHasher&) = delete;
    ContentHasher& operator=(const ContentHasher&) = delete;

    // Each field is hashed with its length first, so that ("ab", "c") and ("a", "bc") differ.
    ContentHasher& add(std::string_view field);
    std::string hex() const;

  private:
    struct State;
    std::unique_ptr<State> state_;
};

// The hash of a file's bytes. Throws ibl::Error "<file>: cannot read" when it cannot be read.
std::string hashFile(const std::filesystem::path& file);

} // namespace ibl
