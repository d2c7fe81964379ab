// OpenEXR output of float images (through OpenEXR), written atomically.
#pragma once

#include "iblbake/core/image.h"

#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace ibl {

enum class PixelType { Half, Float };
// OpenEXR's envmap attribute: how a lat-long or cube-face image maps to directions.
enum class ExrEnvmap { LatLong, Cube };

struct ExrOutputOptions {
    int channels = 4; // 3 writes R, G, B; 4 adds A
    PixelType pixelType = PixelType::Float;
    std::optional<ExrEnvmap> envmap;
    std::vector<std::pair<std::string, std::string>> attributes; // string metadata, e.g. "iblbake:layout"
};

// Throws ibl::Error naming the file and the problem; leaves no partial file and keeps an existing one.
void writeExr(const std::filesystem::path& path, const ImageRGBA& image, const ExrOutputOptions& options);

} // namespace ibl
