// printf-style formatting into a std::string, for the library's text reports (plans, inspections), and the
// replacement of one text by another in a message.
#pragma once

#include <cstdio>
#include <string>

namespace ibl {

// `pattern` with `values` (std::snprintf's conversions), of any length.
template <class... Values>
std::string formatText(const char* pattern, Values... values) {
    std::string text(std::size_t(std::snprintf(nullptr, 0, pattern, values...)) + 1, '\0');
    std::snprintf(text.data(), text.size(), pattern, values...);
    text.pop_back();
    return text;
}

// `text` with every occurrence of `from` replaced by `to` (a message naming a temporary path shown with the
// path the user named).
inline std::string replaceAll(std::string text, const std::string& from, const std::string& to) {
    if (from.empty()) return text;
    for (std::size_t at = text.find(from); at != std::string::npos; at = text.find(from, at + to.size()))
        text.replace(at, from.size(), to);
    return text;
}

} // namespace ibl
