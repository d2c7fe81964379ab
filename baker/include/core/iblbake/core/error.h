// The one exception type of the baker: its message is a complete one-line diagnosis for the user.
#pragma once

#include <cstdio>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>

namespace ibl {

class Error : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

// An Error writing an output file (a full disk, a read-only directory): its message names the output and
// the system's reason, and a caller that puts the input being processed in front of its errors leaves
// this one alone (an input is not to blame for a full disk).
class OutputError : public Error {
  public:
    using Error::Error;
};

// An Error caused by the value of one setting. The message says what is wrong in the library's terms;
// setting() names the setting as its struct field does (e.g. "layout", "sourceFaceSize", "calibration",
// "extractSun"; each throwing function lists its own), so that a caller can put its own name for it in front:
// the CLI its flag, a scene bake the scene's key path.
class SettingError : public Error {
  public:
    SettingError(std::string setting, const std::string& message)
        : Error(message), setting_(std::move(setting)) {}
    const std::string& setting() const { return setting_; }

  private:
    std::string setting_;
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

// Whether text holds a control byte (a line break, an escape): then it cannot go into a message as it is.
inline bool hasControlBytes(std::string_view text) {
    for (const char c : text)
        if (static_cast<unsigned char>(c) < 0x20 || c == 0x7F) return true;
    return false;
}

// Text longer than this goes into a message shortened (quotedForMessage): a 10 MB key must not make a
// 10 MB line.
inline constexpr std::size_t kMaxMessageTextBytes = 256;

// A key or path from an input file for a message: as it is (UTF-8 included), or quotedForMessage when it
// holds control bytes or is longer than kMaxMessageTextBytes, so the message stays one short line (found
// by the fuzz targets of fuzz/).
inline std::string printableForMessage(std::string_view text) {
    return hasControlBytes(text) || text.size() > kMaxMessageTextBytes ? quotedForMessage(text)
                                                                       : std::string(text);
}

// A value from an input file for a message: in single quotes, escaped and shortened like quotedForMessage
// when it holds control bytes or is long.
inline std::string valueForMessage(std::string_view value) {
    if (hasControlBytes(value) || value.size() > kMaxMessageTextBytes) return quotedForMessage(value);
    std::string out = "'";
    out.append(value);
    return out += '\'';
}

} // namespace ibl
