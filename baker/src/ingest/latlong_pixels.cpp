// Names of the lat-long pixel placements (iblbake/baker/latlong_pixels.h).
#include "iblbake/baker/latlong_pixels.h"

#include "iblbake/core/error.h"

namespace ibl {

LatLongPixels parseLatLongPixels(const std::string& name) {
    if (name == "auto") return LatLongPixels::Auto;
    if (name == "centre" || name == "center") return LatLongPixels::Centre;
    if (name == "openexr") return LatLongPixels::OpenExr;
    throw SettingError("latLongPixels", "'" + name + "' is not one of auto, centre, openexr");
}

const char* latLongPixelsName(LatLongPixels placement) {
    switch (placement) {
    case LatLongPixels::Centre:
        return "centre";
    case LatLongPixels::OpenExr:
        return "openexr";
    case LatLongPixels::Auto:
        break;
    }
    return "auto";
}

} // namespace ibl
