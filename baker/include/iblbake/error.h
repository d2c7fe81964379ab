// The one exception type of the baker: its message is a complete one-line diagnosis for the user.
#pragma once

#include <cstdio>
#include <stdexcept>
#include <string>
#include <string_view>

namespace ibl {

class Error : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

// Text taken from an input file, made safe to quote in an Error: bytes outside printable ASCII become
// \xNN (a damaged file's key may hold line breaks or control codes) and more than 64 bytes are cut to
// "...", so the message stays one readable line.
inline std::string quotedForMessage(std::string_view text) {
    constexpr std::size_t kMaxBytes = 64;
    std::string out = "'";
    for (std::size_t i = 0; i < text.size() && i < kMaxBytes; ++i) {
        const unsigned char c = static_cast<unsigned char>(text[i]);
        if (c >= 0x20 && c < 0x7F && c != '\\') {
            out += char(c);
        } else {
            char escaped[5];
            std::snprintf(escaped, sizeof escaped, "\\x%02X", c);
            out += escaped;
        }
    }
    if (text.size() > kMaxBytes) out += "...";
    return out + "'";
}

} // namespace ibl
