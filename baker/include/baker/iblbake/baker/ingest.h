// Ingest: from HDR file(s) on disk to a sanitized, linear, working-space source cube map
// (docs/architecture.md "From HDRI to engine": OIIO -> float image -> OCIO -> working linear RGB -> sanitize
// -> source cube).
#pragma once

#include "iblbake/baker/latlong_pixels.h"
#include "iblbake/core/cubemap.h"
#include "iblbake/core/image.h"

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace ibl {

// How the environment is laid out in the input. Cube layouts other than ExrCube hold faces in our
// order and OpenGL orientation (kernels/cube.h); the crosses unfold the cube around +Z:
//
//   HorizontalCross (4:3)      VerticalCross (3:4)
//        . +Y .  .                  .  +Y  .
//       -X +Z +X -Z                -X  +Z  +X
//        . -Y .  .                  .  -Y  .
//                                   .  -Z' .     -Z' = -Z rotated by 180 degrees
//
// Every face sits unrotated in the horizontal cross, which makes it a true unfolding: +Y's last row
// touches +Z's first row, -Y's first row touches +Z's last row, and along row 1 each face's right column
// touches the next face's left column. The vertical cross is the same unfolding with -Z hung below -Y,
// where it has to be turned upside down (its last row touches -Y's last row).
enum class EnvLayout {
    Auto,
    LatLong,         // equirect, docs/conventions.md lat-long mapping (OpenEXR LatLongMap), pixels by
                     // latlong_pixels.h
    ExrCube,         // OpenEXR envmap=cube: 6 faces stacked vertically, ImfEnvmap CubeMap convention
    HorizontalCross, // 4:3, see above
    VerticalCross,   // 3:4, see above
    HorizontalStrip, // 6:1, faces side by side in +X, -X, +Y, -Y, +Z, -Z order, OpenGL orientation
    VerticalStrip,   // 1:6, faces stacked in +X, -X, +Y, -Y, +Z, -Z order, OpenGL orientation
    SixFiles         // one square file per face, given in +X, -X, +Y, -Y, +Z, -Z order
};

// Accepts the layoutName() spellings (auto, latlong, exr-cube, hcross, vcross, hstrip, vstrip, six-files)
// and a few common synonyms; throws ibl::SettingError ("layout") naming the accepted values otherwise.
EnvLayout parseLayout(const std::string& name);
const char* layoutName(EnvLayout layout);

struct IngestSettings {
    EnvLayout layout = EnvLayout::Auto;
    // Colour space of the input, a name (or alias) in the OCIO config. "" = from the file's metadata
    // (oiio:ColorSpace, EXR chromaticities); when that says nothing: sRGB for 8-bit files, else lin_rec709.
    std::string inputColorSpace;
    std::string workingColorSpace = "lin_rec709"; // or "acescg"; must be a linear space of the config
    // Rotation of the environment about +Y in degrees; positive turns it counter-clockwise seen from
    // above (+Z toward +X). Never implicit.
    float rotateDegrees = 0.0f;
    // Face size of the source cube. 0 = from the input: a lat-long's width / 4 rounded to the nearest
    // power of two, a cube's own face size.
    int sourceFaceSize = 0;
    // Where a lat-long's pixels sit (latlong_pixels.h): Auto = OpenExr for a file carrying OpenEXR's envmap
    // = latlong attribute, else pixel centres. Not used by cube layouts.
    LatLongPixels latLongPixels = LatLongPixels::Auto;
    // Read the file's alpha channel as a visibility (a local probe's capture, Frostbite 2014 4.9.1.2: 1 for
    // the close surroundings, 0 for sky). Colour is then taken as premultiplied by it (OpenEXR's associated
    // alpha; a file that declares unassociated alpha, e.g. PNG, is premultiplied after its colour
    // conversion) and resampled with it by the same exact-area weights. false: alpha is ignored (every
    // texel 1), as for the distant environment.
    bool readAlpha = false;
    // With readAlpha: the visibility as separate images, one per input file and of its size, replacing the
    // file's alpha. Channel R (a grey image's only one) as stored, no colour conversion (a coverage, not a
    // colour; an 8-bit file's 0-255 read as 0-1); the input's colour is then straight, premultiplied by it
    // after its colour conversion. Empty: the file's own alpha channel, if any.
    std::vector<std::filesystem::path> visibilityMask;
};

struct IngestReport {
    std::string file; // the (first) input file
    int width = 0;    // of the (first) input image
    int height = 0;
    EnvLayout layout = EnvLayout::Auto; // as detected or given
    std::string inputColorSpace, workingColorSpace;
    // Repaired values, counted per colour channel value (not per pixel). NaN -> 0; +Inf -> the largest
    // finite value in the image (65504 if there is none); -Inf and negatives -> 0, both before and after
    // the colour conversion (a gamut change can make values negative).
    std::uint64_t nanRepaired = 0, infRepaired = 0, negativeRepaired = 0;
    float maxLuminanceIn = 0.0f; // brightest input pixel's luminance after colour conversion and repair
    int faceSize = 0;            // of the source cube
    // The placement a lat-long input was read with (Centre or OpenExr); nothing for cube layouts.
    std::optional<LatLongPixels> latLongPixels;
    // With readAlpha: whether the cube carries a visibility (the file has an alpha channel and some value of
    // it, after repair, is not 1; a file whose alpha is 1 everywhere ingests as one without alpha), and the
    // alpha values repaired, counted per pixel: NaN and negatives (-Inf included) make the pixel transparent
    // (RGBA 0, as bakeSpecularWithVisibility takes them), values over 1 (+Inf included) become 1.
    bool hasAlpha = false;
    std::uint64_t alphaNanRepaired = 0, alphaNegativeRepaired = 0, alphaOverOneRepaired = 0;
};

struct SourceEnvironment {
    // Working-space linear RGB; A = 1, or with IngestReport::hasAlpha the visibility in [0, 1] and RGB
    // premultiplied by it.
    CubeMap cube;
    IngestReport report;
};

// files: one file, or six for EnvLayout::SixFiles. Throws ibl::Error with a one-line message naming the
// file and the problem; an ibl::SettingError when one setting is the cause, setting() naming its field
// ("layout", "inputColorSpace", "workingColorSpace", "rotateDegrees", "sourceFaceSize", "latLongPixels").
SourceEnvironment ingestEnvironment(const std::vector<std::filesystem::path>& files,
                                    const IngestSettings& settings);

// Area-correct lat-long -> cube resampling (exposed for tests): each cube texel gets the solid-angle
// average of the lat-long over the texel's exact footprint, the lat-long being constant over each pixel.
// Pixel (x, y) covers the cell `placement` gives it (latlong_pixels.h; Centre or OpenExr). Sum of
// value * solid angle is kept.
CubeMap resampleLatLongToCube(const ImageRGBA& latlong, int faceSize, LatLongPixels placement);

} // namespace ibl
