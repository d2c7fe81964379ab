// Layout names and detection: metadata first (OIIO "textureformat", set from OpenEXR's envmap attribute,
// and "oiio:updirection"), then the aspect ratio.
#include "ingest_internal.h"

#include "iblbake/core/error.h"

#include <algorithm>
#include <cctype>

namespace ibl {

namespace {

std::string lower(std::string s) {
    std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return s;
}

} // namespace

EnvLayout parseLayout(const std::string& name) {
    const std::string n = lower(name);
    if (n == "auto") return EnvLayout::Auto;
    if (n == "latlong" || n == "lat-long" || n == "latlon" || n == "equirect" || n == "equirectangular")
        return EnvLayout::LatLong;
    if (n == "exr-cube" || n == "exrcube" || n == "cube") return EnvLayout::ExrCube;
    if (n == "hcross" || n == "horizontal-cross") return EnvLayout::HorizontalCross;
    if (n == "vcross" || n == "vertical-cross") return EnvLayout::VerticalCross;
    if (n == "hstrip" || n == "horizontal-strip") return EnvLayout::HorizontalStrip;
    if (n == "vstrip" || n == "vertical-strip") return EnvLayout::VerticalStrip;
    if (n == "six-files" || n == "faces" || n == "6files") return EnvLayout::SixFiles;
    throw SettingError("layout",
                       "'" + name +
                           "' is not one of auto, latlong, exr-cube, hcross, vcross, hstrip, vstrip, "
                           "six-files");
}

const char* layoutName(EnvLayout layout) {
    switch (layout) {
    case EnvLayout::LatLong:
        return "latlong";
    case EnvLayout::ExrCube:
        return "exr-cube";
    case EnvLayout::HorizontalCross:
        return "hcross";
    case EnvLayout::VerticalCross:
        return "vcross";
    case EnvLayout::HorizontalStrip:
        return "hstrip";
    case EnvLayout::VerticalStrip:
        return "vstrip";
    case EnvLayout::SixFiles:
        return "six-files";
    default:
        return "auto";
    }
}

namespace ingest {

namespace {

std::string sizeText(int w, int h) {
    return std::to_string(w) + "x" + std::to_string(h);
}

// Throws when a requested layout does not fit the image size.
void checkSize(const RawImage& image, EnvLayout layout) {
    const int w = image.pixels.width, h = image.pixels.height;
    auto fail = [&](const char* need) {
        throw Error(image.file + ": layout " + layoutName(layout) + " needs " + need + ", but the image is " +
                    sizeText(w, h));
    };
    switch (layout) {
    case EnvLayout::LatLong:
        // The mapping works for any size, but far from 2:1 the input is surely something else.
        if (w < 2 || w < h || w > 4 * h) fail("a lat-long image of about 2:1 (between 1:1 and 4:1)");
        break;
    case EnvLayout::ExrCube:
    case EnvLayout::VerticalStrip:
        if (h != 6 * w) fail("a 1:6 image (six square faces stacked vertically)");
        break;
    case EnvLayout::HorizontalStrip:
        if (w != 6 * h) fail("a 6:1 image (six square faces side by side)");
        break;
    case EnvLayout::HorizontalCross:
        if (w % 4 != 0 || 3 * w != 4 * h) fail("a 4:3 image whose width is a multiple of 4");
        break;
    case EnvLayout::VerticalCross:
        if (h % 4 != 0 || 3 * h != 4 * w) fail("a 3:4 image whose height is a multiple of 4");
        break;
    case EnvLayout::SixFiles:
        if (w != h) fail("square images");
        break;
    case EnvLayout::Auto:
        break;
    }
}

EnvLayout detect(const RawImage& image) {
    const int w = image.pixels.width, h = image.pixels.height;
    // OpenImageIO turns OpenEXR's envmap attribute into textureformat; maketx writes the same names.
    if (image.textureFormat == "LatLong Environment") {
        // OIIO's default for lat-long textures is RenderMan's z-up, left-handed convention; only the
        // y-up OpenEXR convention is ours, and guessing a mirror image silently would be worse than asking.
        if (!image.upDirection.empty() && lower(image.upDirection) != "y")
            throw SettingError("layout",
                               image.file + ": lat-long with oiio:updirection '" + image.upDirection +
                                   "' (not the OpenEXR y-up convention); give the layout latlong to "
                                   "read it as y-up");
        return EnvLayout::LatLong;
    }
    if (image.textureFormat == "CubeFace Environment" && h == 6 * w) return EnvLayout::ExrCube;
    if (w == 2 * h) return EnvLayout::LatLong;
    if (h == 6 * w) return EnvLayout::VerticalStrip;
    if (w == 6 * h) return EnvLayout::HorizontalStrip;
    if (w % 4 == 0 && 3 * w == 4 * h) return EnvLayout::HorizontalCross;
    if (h % 4 == 0 && 3 * h == 4 * w) return EnvLayout::VerticalCross;
    throw SettingError("layout", image.file + ": cannot tell the layout of a " + sizeText(w, h) +
                                     " image; give the layout");
}

} // namespace

LatLongPixels resolveLatLongPixels(const RawImage& image, LatLongPixels requested) {
    return ibl::resolveLatLongPixels(requested, image.textureFormat == "LatLong Environment");
}

EnvLayout resolveLayout(const RawImage& image, EnvLayout requested) {
    const EnvLayout layout = requested == EnvLayout::Auto ? detect(image) : requested;
    checkSize(image, layout);
    return layout;
}

} // namespace ingest

} // namespace ibl
