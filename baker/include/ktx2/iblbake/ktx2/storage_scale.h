// The storage scale of a product file (docs/conventions.md "Float storage and the storage scale"; Frostbite
// 2014 section 5.2, whose pre-exposure stores lighting times a known factor so that it fits a 16-bit float
// target): a product whose values exceed its format's range is stored times a recorded power of two, and
// every reader divides it out again. KTX2 key "iblbake.storageScale": stored RGB = radiance x storageScale
// (alpha is stored as is); absent in files of older iblbake, which means 1.
#pragma once

#include "iblbake/ktx2/ktx2.h"

#include <glm/vec3.hpp>

namespace ibl {

inline constexpr const char* kStorageScaleKey = "iblbake.storageScale";

// The largest finite value each of R, G, B of `format` stores (RGBA16F 65,504 each; B10G11R11 65,024 for
// R and G, 64,512 for the 10-bit B; E5B9G9R9 65,408; RGBA32F FLT_MAX).
glm::vec3 ktx2LargestValues(Ktx2Format format);

// The file's iblbake.storageScale, 1 when absent. Throws ibl::Error "iblbake.storageScale: '<value>' is
// not a positive finite number" for any other value (the caller adds the file).
double ktx2StorageScale(const Ktx2Image& image);

// The image's texels back in radiance: RGB / ktx2StorageScale(image) (alpha untouched); a no-op at 1.
void unscaleKtx2Texels(Ktx2Image& image);

} // namespace ibl
