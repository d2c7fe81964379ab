#include "encoded_image.h"

#include "iblbake/core/error.h"
#include "iblbake/ktx2/atomic_file.h"

#include <OpenImageIO/filesystem.h>

#include <string_view>
#include <vector>

namespace ibl {

void writeEncodedImage(const std::filesystem::path& path, const char* format, OIIO::ImageSpec spec,
                       OIIO::TypeDesc type, const void* pixels, OIIO::stride_t stride) {
    AtomicFile file(path);
    std::vector<unsigned char> encoded;
    OIIO::Filesystem::IOVecOutput memory(encoded);
    auto out = OIIO::ImageOutput::create(format, &memory);
    if (!out)
        throw OutputError(path.string() + ": cannot create a " + format + " writer: " + OIIO::geterror());
    void* proxy = &memory;
    spec.attribute("oiio:ioproxy", OIIO::TypeDesc::PTR, &proxy);
    if (!out->open(file.tempPath().string(), spec)) throw OutputError(path.string() + ": " + out->geterror());
    bool ok = out->write_image(type, pixels, stride);
    ok = out->close() && ok;
    if (!ok) throw OutputError(path.string() + ": " + out->geterror());
    writeFileBytes(file.tempPath(),
                   std::string_view(reinterpret_cast<const char*>(encoded.data()), encoded.size()),
                   path.string());
    file.commit();
}

} // namespace ibl
