// The specular chain's settings checked before any work (limits.h): a level count or sample count out of
// range is refused with its range, not clamped silently (--levels 1e9, -1 and 0 used to give a full chain).
#include "iblbake/baker/specular.h"

#include "iblbake/core/error.h"
#include "iblbake/core/limits.h"

#include <string>

namespace ibl {

void validateSpecularSettings(const SpecularSettings& settings, int faceSize) {
    if (faceSize < 1 || faceSize > limits::kMaxFaceSize || (faceSize & (faceSize - 1)) != 0)
        throw SettingError("faceSize", std::to_string(faceSize) + " is not a power of two from 1 to " +
                                           std::to_string(limits::kMaxFaceSize));
    const int full = mipLevelCount(faceSize);
    if (settings.levels < 0 || settings.levels > full)
        throw SettingError("levels", "the level count " + std::to_string(settings.levels) +
                                         " is not from 1 to " + std::to_string(full) + " (a " +
                                         std::to_string(faceSize) + "-px face down to 1x1)");
    if (settings.samples > limits::kMaxSamples)
        throw SettingError("samples", "the sample count " + std::to_string(settings.samples) +
                                          " is not from 1 to " + std::to_string(limits::kMaxSamples));
}

Backend standaloneSpecularBackend(Backend requested, bool deviceNamed, const SpecularSettings& settings,
                                  int faceSize) {
    const bool small = faceSize <= kStandaloneCpuFaceSize &&
                       samplesFor(settings) <= samplesFor(SpecularSettings{}); // the production preset
    return requested == Backend::Auto && !deviceNamed && small ? Backend::Cpu : requested;
}

} // namespace ibl
