// Synthetic environments on SphereTexels grids (environment_stats.h), for the calibration and sun tests.
#pragma once

#include <iblbake/baker/environment_stats.h>

#include <functional>

namespace ibl::test {

using DirectionalRadiance = std::function<glm::vec3(const glm::dvec3&)>;

// A cube whose texels hold value(direction), through SphereTexels' own texel directions; alpha 1.
inline CubeMap cubeOf(int n, const DirectionalRadiance& value) {
    CubeMap cube(n);
    for (ImageRGBA& f : cube.faces)
        for (glm::vec4& p : f.pixels)
            p = glm::vec4(0, 0, 0, 1);
    SphereTexels t(cube);
    for (std::size_t i = 0; i < t.size(); ++i)
        t.setRgb(i, value(t.direction(i)));
    return cube;
}

// The same on a w x h lat-long whose pixels sit where `placement` puts them (latlong_pixels.h).
inline ImageRGBA latLongOf(int w, int h, const DirectionalRadiance& value,
                           LatLongPixels placement = LatLongPixels::Centre) {
    ImageRGBA im(w, h);
    for (glm::vec4& p : im.pixels)
        p = glm::vec4(0, 0, 0, 1);
    SphereTexels t(im, placement);
    for (std::size_t i = 0; i < t.size(); ++i)
        t.setRgb(i, value(t.direction(i)));
    return im;
}

} // namespace ibl::test
