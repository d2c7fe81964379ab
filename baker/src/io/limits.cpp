#include "iblbake/core/limits.h"

#include "iblbake/core/error.h"

#include <charconv>
#include <cstdlib>
#include <cstring>

namespace ibl::limits {

std::uint64_t maxImagePixels() {
    const char* text = std::getenv(kMaxImagePixelsVariable);
    if (!text || !*text) return kDefaultMaxImagePixels;
    constexpr std::uint64_t kMost = std::uint64_t(1) << 40;
    std::uint64_t value = 0;
    const char* end = text + std::strlen(text);
    const auto [at, error] = std::from_chars(text, end, value);
    if (error != std::errc() || at != end || value < 1 || value > kMost)
        throw Error(std::string(kMaxImagePixelsVariable) + ": " + valueForMessage(text) +
                    " is not a whole number of pixels from 1 to " + std::to_string(kMost));
    return value;
}

} // namespace ibl::limits
