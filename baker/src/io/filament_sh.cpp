// Filament's sh.txt (iblbake/baker/filament_sh.h).
#include "iblbake/baker/filament_sh.h"
#include "iblbake/core/numeric.h"

#include <cstdio>

namespace ibl {

std::string filamentShText(const ShRgb& prescaledIrradiance) {
    constexpr const char* kNames[9] = {"L00", "L1-1", "L10", "L11", "L2-2", "L2-1", "L20", "L21", "L22"};
    std::string text;
    for (std::size_t i = 0; i < 9; ++i) {
        const glm::dvec3 c = prescaledIrradiance[i] / kPi;
        char line[160];
        std::snprintf(line, sizeof line, "(%.9g, %.9g, %.9g); // %s, irradiance, pre-scaled base\n", c.x, c.y,
                      c.z, kNames[i]);
        text += line;
    }
    return text;
}

std::string filamentShMetadata(const ShRgb& prescaledIrradiance) {
    std::string text;
    for (const glm::dvec3& irradiance : prescaledIrradiance) {
        const glm::dvec3 c = irradiance / kPi;
        char line[96];
        std::snprintf(line, sizeof line, "%.9g %.9g %.9g\n", c.x, c.y, c.z);
        text += line;
    }
    return text;
}

} // namespace ibl
