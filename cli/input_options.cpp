#include "input_options.h"

#include <iblbake/core/limits.h>

namespace ibl::cli {

void InputOptions::addTo(CLI::App& command) {
    command.add_option("input", inputs, "HDR environment (one file, or six for --layout six-files)")
        ->required();
    command
        .add_option("--layout", layout, "auto, latlong, exr-cube, hcross, vcross, hstrip, vstrip, six-files")
        ->capture_default_str();
    command.add_option("--input-colorspace", inputColorSpace,
                       "input colour space (default: file metadata, else lin_rec709; sRGB for 8-bit files)");
    command.add_option("--working-colorspace", workingColorSpace, "lin_rec709 or acescg")
        ->capture_default_str();
    command.add_option("--rotate", rotateDegrees, "rotate the environment about +Y, degrees")
        ->capture_default_str();
    addLatLongPixelsOption(command, latLongPixels);
}

void OneInputOptions::addTo(CLI::App& command, const char* sizeHelp) {
    command.add_option("input", input, "HDR environment")->required();
    command.add_option("--size", size, sizeHelp)->check(CLI::Range(0, limits::kMaxFaceSize));
    command.add_option("--layout", layout, "auto, latlong, exr-cube, hcross, vcross, hstrip, vstrip")
        ->capture_default_str();
    command.add_option("--input-colorspace", inputColorSpace,
                       "input colour space (default: file metadata, else lin_rec709; sRGB for 8-bit files)");
    addLatLongPixelsOption(command, latLongPixels);
}

IngestSettings OneInputOptions::settings() const {
    IngestSettings s;
    s.layout = parseLayout(layout);
    s.inputColorSpace = inputColorSpace;
    s.sourceFaceSize = size;
    s.latLongPixels = parseLatLongPixels(latLongPixels);
    return s;
}

void addLatLongPixelsOption(CLI::App& command, std::string& latLongPixels) {
    command
        .add_option("--latlong-pixels", latLongPixels,
                    "where a lat-long's pixels sit: centre (u = (x+0.5)/W), openexr (u = x/(W-1), "
                    "ImfEnvmap LatLongMap), auto (openexr for files with the envmap attribute, else centre)")
        ->capture_default_str();
}

IngestSettings InputOptions::settings(int sourceFaceSize) const {
    IngestSettings s;
    s.layout = parseLayout(layout);
    s.inputColorSpace = inputColorSpace;
    s.workingColorSpace = workingColorSpace;
    s.rotateDegrees = rotateDegrees;
    s.sourceFaceSize = sourceFaceSize;
    s.latLongPixels = parseLatLongPixels(latLongPixels);
    return s;
}

} // namespace ibl::cli
