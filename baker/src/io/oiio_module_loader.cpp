// Loading the OpenImageIO module (oiio_module.h) once per process, on first use.
#include "oiio_module.h"
#include "shipped_file.h"

#include "iblbake/core/error.h"

#include <dlfcn.h>
#include <mutex>

namespace ibl::oiio_module {

namespace {

struct Loaded {
    const Api* api = nullptr;
    std::string failure;
};

Loaded load() {
    const std::string path = shippedFile(IBLBAKE_INSTALLED_OIIO_MODULE, IBLBAKE_BUILD_OIIO_MODULE);
    // RTLD_LOCAL: OpenImageIO's libraries serve the module alone; the module stays loaded until exit.
    void* handle = ::dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!handle) return {nullptr, printableForMessage(::dlerror())};
    auto entry = reinterpret_cast<const Api* (*)()>(::dlsym(handle, "iblbakeOiioModule"));
    if (!entry) return {nullptr, path + " has no iblbakeOiioModule"};
    return {entry(), {}};
}

} // namespace

const Api& api(const std::string& what) {
    static std::once_flag once;
    static Loaded loaded;
    std::call_once(once, [] { loaded = load(); });
    if (!loaded.api) throw Error(what + " needs iblbake's OpenImageIO module: " + loaded.failure);
    return *loaded.api;
}

} // namespace ibl::oiio_module
