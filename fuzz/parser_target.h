// The contract every fuzz target checks for a parser of untrusted input: each input either parses or is
// refused with ibl::Error whose message is one non-empty line naming the input (house rule for bad
// input). Any other outcome is a finding: libFuzzer reports a crash, a hang, an escaping exception or
// excessive memory; AddressSanitizer/UndefinedBehaviorSanitizer report the rest; a malformed refusal
// aborts here.
#pragma once

#include <iblbake/core/error.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <span>
#include <string>

namespace ibl::fuzz {

// Runs parse(bytes, name); returns 0 as LLVMFuzzerTestOneInput must.
template <class Parse>
int parseOrRefuse(const std::uint8_t* data, std::size_t size, const std::string& name, Parse parse) {
    try {
        parse(std::span<const std::uint8_t>(data, size), name);
    } catch (const ibl::Error& e) {
        const std::string message = e.what();
        if (message.empty() || message.find('\n') != std::string::npos ||
            message.find(name) == std::string::npos) {
            std::fprintf(stderr, "refusal is not one line naming '%s': '%s'\n", name.c_str(),
                         message.c_str());
            std::abort();
        }
    }
    return 0;
}

} // namespace ibl::fuzz
