// Ktx2Format by name (iblbake/ktx2/ktx2.h).
#include "iblbake/core/error.h"
#include "iblbake/ktx2/ktx2.h"

namespace ibl {

Ktx2Format parseKtx2Format(const std::string& name) {
    std::string list;
    for (std::size_t i = 0; i < kKtx2FormatNames.size(); ++i) {
        if (name == kKtx2FormatNames[i]) return Ktx2Format(i);
        list += (i ? ", " : "") + kKtx2FormatNames[i];
    }
    throw Error(quotedForMessage(name) + " is not one of " + list);
}

} // namespace ibl
