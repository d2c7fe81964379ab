// The one-line form of an error message, for the commands' one line per error on stderr.
#pragma once

#include <string>

namespace ibl {

// A message as one line: library messages (OpenImageIO, OpenEXR, an OpenCL build log) may span lines; a
// command's contract is one line per error, so line breaks become "; " (trailing ones and spaces go).
inline std::string oneLine(std::string message) {
    while (!message.empty() && (message.back() == '\n' || message.back() == ' '))
        message.pop_back();
    std::string out;
    for (std::size_t i = 0; i < message.size(); ++i) {
        if (message[i] != '\n') {
            out += message[i];
            continue;
        }
        while (i + 1 < message.size() && message[i + 1] == '\n')
            ++i;
        out += "; ";
    }
    return out;
}

} // namespace ibl
