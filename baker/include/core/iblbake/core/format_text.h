// printf-style formatting into a std::string, for the library's text reports (plans, inspections).
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

} // namespace ibl
