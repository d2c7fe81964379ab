// Small numeric facts that many library files use, each defined here once: pi and the degree in double,
// the power-of-two test of face and LUT sizes, Rec.709 luminance, and float-exact decimal text
// (docs/conventions.md "Units and calibration").
#pragma once

#include <bit>
#include <cstdio>
#include <numbers>
#include <string>

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

namespace ibl {

inline constexpr double kPi = std::numbers::pi;
inline constexpr double kDegree = kPi / 180.0; // one degree in radians

// Rec.709 / lin_rec709 luminance weights (0.2126 R + 0.7152 G + 0.0722 B).
inline constexpr glm::dvec3 kRec709Luminance{0.2126, 0.7152, 0.0722};

// Rec.709 luminance in float, for image-sized loops (the bright-texel split, previews).
inline float rec709Luminance(const glm::vec3& rgb) {
    return 0.2126f * rgb.x + 0.7152f * rgb.y + 0.0722f * rgb.z;
}
inline float rec709Luminance(const glm::vec4& rgba) {
    return rec709Luminance(glm::vec3(rgba));
}

inline bool isPowerOfTwo(int value) {
    return value > 0 && std::has_single_bit(unsigned(value));
}

// `value` as text with 9 significant digits: enough that a float read back from it is the very float
// written (metadata values that a loader parses again, and numbers in messages).
inline std::string floatDecimal(double value) {
    char text[32];
    std::snprintf(text, sizeof text, "%.9g", value);
    return text;
}

} // namespace ibl
