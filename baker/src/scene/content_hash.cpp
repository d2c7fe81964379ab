#include "iblbake/bake_state/content_hash.h"

#include "iblbake/core/error.h"
#include "iblbake/core/input_file.h"

#include <xxhash.h>

#include <cstdint>
#include <cstdio>
#include <memory>
#include <vector>

namespace ibl {

namespace {

// Big-endian canonical form (xxHash's own), so the text is the same on every machine.
std::string toHex(XXH128_hash_t hash) {
    XXH128_canonical_t canonical;
    XXH128_canonicalFromHash(&canonical, hash);
    std::string out;
    char digits[3];
    for (unsigned char byte : canonical.digest) {
        std::snprintf(digits, sizeof digits, "%02x", byte);
        out += digits;
    }
    return out;
}

} // namespace

struct ContentHasher::State {
    XXH3_state_t* xxh = XXH3_createState();
    ~State() { XXH3_freeState(xxh); }
};

ContentHasher::ContentHasher() : state_(std::make_unique<State>()) {
    if (!state_->xxh) throw Error("content hash: out of memory");
    XXH3_128bits_reset(state_->xxh);
}

ContentHasher::~ContentHasher() = default;

ContentHasher& ContentHasher::add(std::string_view field) {
    const std::uint64_t size = field.size();
    XXH3_128bits_update(state_->xxh, &size, sizeof size);
    XXH3_128bits_update(state_->xxh, field.data(), field.size());
    return *this;
}

std::string ContentHasher::hex() const {
    return toHex(XXH3_128bits_digest(state_->xxh));
}

std::string hashFile(const std::filesystem::path& file) {
    InputFile in(file); // a device or FIFO is refused here, before it is read without end
    const std::unique_ptr<XXH3_state_t, decltype(&XXH3_freeState)> state(XXH3_createState(), &XXH3_freeState);
    if (!state) throw Error("content hash: out of memory");
    XXH3_128bits_reset(state.get());
    std::vector<char> buffer(1 << 20);
    while (const std::size_t n = in.read(buffer.data(), buffer.size()))
        XXH3_128bits_update(state.get(), buffer.data(), n);
    return toHex(XXH3_128bits_digest(state.get()));
}

} // namespace ibl
