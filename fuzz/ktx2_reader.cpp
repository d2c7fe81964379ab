// Fuzz target: the KTX2 reader (baker/src/io/ktx2_reader.cpp) on arbitrary bytes. Seeds: ktx2_seeds.cpp.
#include "parser_target.h"

#include <iblbake/ktx2/ktx2.h>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    return ibl::fuzz::parseOrRefuse(data, size, "fuzz.ktx2",
                                    [](auto bytes, const std::string& name) { ibl::parseKtx2(bytes, name); });
}
