// The repair rule of a premultiplied colour + visibility texel (docs/conventions.md, visibility convention),
// one definition for ingest, the specular stage and the runtime's probe loader: a visibility in [0, 1] is
// kept; above 1 it is 1 (the colour kept); NaN or negative is a transparent texel, RGBA 0, since colour
// premultiplied by a visibility without meaning has no meaning to keep.
#pragma once

#include <glm/vec4.hpp>

namespace ibl {

enum class VisibilityRepair { None, OverOne, Negative, NaN };

inline VisibilityRepair visibilityRepairOf(float visibility) {
    if (visibility >= 0.0f && visibility <= 1.0f) return VisibilityRepair::None; // false for NaN
    if (visibility > 1.0f) return VisibilityRepair::OverOne;
    return visibility < 0.0f ? VisibilityRepair::Negative : VisibilityRepair::NaN;
}

inline glm::vec4 repairedVisibilityTexel(const glm::vec4& texel, VisibilityRepair repair) {
    switch (repair) {
    case VisibilityRepair::None:
        return texel;
    case VisibilityRepair::OverOne:
        return glm::vec4(texel.x, texel.y, texel.z, 1.0f);
    default:
        return glm::vec4(0.0f);
    }
}

inline glm::vec4 repairedVisibilityTexel(const glm::vec4& texel) {
    return repairedVisibilityTexel(texel, visibilityRepairOf(texel.w));
}

} // namespace ibl
