// Conversions between fp32 and the small float encodings stored in KTX2 files: IEEE half, the unsigned
// 11- and 10-bit floats of B10G11R11 and the shared-exponent E5B9G9R9 (Vulkan spec, "Fixed-Point and
// Floating-Point Data Conversions"). Encoders expect finite inputs already clamped to the format's range
// (the writer sanitizes first), so they never produce Inf/NaN codes.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>

namespace ibl::smallfloat {

// All three small float encodings share a 5-bit exponent with bias 15 and differ in mantissa width.
inline constexpr int kExponentBias = 15;

inline constexpr float kHalfMax = 65504.0f;    // (2 - 2^-10) * 2^15
inline constexpr float kFloat11Max = 65024.0f; // (2 - 2^-6) * 2^15
inline constexpr float kFloat10Max = 64512.0f; // (2 - 2^-5) * 2^15
inline constexpr float kRgb9e5Max = 65408.0f;  // (511 / 512) * 2^16

// |v| encoded with `mantissaBits` and a 5-bit exponent, rounded to nearest, ties to even. The result is
// exponent << mantissaBits | mantissa, without sign. Requires |v| <= the format's largest finite value.
inline std::uint32_t encodeMagnitude(float v, int mantissaBits) {
    std::uint32_t x;
    std::memcpy(&x, &v, sizeof x);
    x &= 0x7FFFFFFFu;
    if (x < 0x00800000u) return 0;    // zero or an fp32 subnormal: far below half the smallest code
    const int e = int(x >> 23) - 127; // value = m * 2^(e - 23)
    const std::uint32_t m = (x & 0x007FFFFFu) | 0x00800000u;
    // Keep `mantissaBits` fraction bits for normal results; below 2^-14 the step stays 2^(-14-mantissaBits)
    // (subnormals). `shift` is how many low bits of m fall below that step.
    const int eClamped = std::max(e, 1 - kExponentBias);
    const int shift = (eClamped - mantissaBits) - (e - 23);
    if (shift >= 25) return 0; // m < 2^24 <= half a step: rounds to zero
    std::uint32_t q = m >> shift;
    const std::uint32_t rest = m & ((1u << shift) - 1u);
    const std::uint32_t half = 1u << (shift - 1);
    // Without a branch: half the values round up, unpredictably (the 1k sample's chain encoded in 26 -> 11 ms
    // with the writer's direct stores).
    q += std::uint32_t(rest > half) | (std::uint32_t(rest == half) & q & 1u);
    // q carries the implicit bit for normal values, so adding it to (exponent - 1) << mantissaBits yields
    // the right code; a mantissa that rounds up to 2^(mantissaBits+1) carries into the exponent.
    return (std::uint32_t(eClamped + kExponentBias - 1) << mantissaBits) + q;
}

inline float decodeMagnitude(std::uint32_t code, int mantissaBits) {
    const std::uint32_t exponent = (code >> mantissaBits) & 31u;
    const std::uint32_t mantissa = code & ((1u << mantissaBits) - 1u);
    if (exponent == 31) return mantissa ? NAN : INFINITY;
    if (exponent == 0) return std::ldexp(float(mantissa), 1 - kExponentBias - mantissaBits);
    return std::ldexp(float(mantissa | (1u << mantissaBits)), int(exponent) - kExponentBias - mantissaBits);
}

inline std::uint16_t floatToHalf(float v) {
    const std::uint32_t sign = std::signbit(v) ? 0x8000u : 0u;
    return std::uint16_t(sign | encodeMagnitude(v, 10));
}

inline float halfToFloat(std::uint16_t h) {
    const float magnitude = decodeMagnitude(h & 0x7FFFu, 10);
    return (h & 0x8000u) ? -magnitude : magnitude;
}

// VK_FORMAT_B10G11R11_UFLOAT_PACK32: R in bits 0..10, G in 11..21, B in 22..31. Inputs in [0, max].
inline std::uint32_t packB10G11R11(float r, float g, float b) {
    return encodeMagnitude(r, 6) | (encodeMagnitude(g, 6) << 11) | (encodeMagnitude(b, 5) << 22);
}

inline void unpackB10G11R11(std::uint32_t p, float& r, float& g, float& b) {
    r = decodeMagnitude(p & 0x7FFu, 6);
    g = decodeMagnitude((p >> 11) & 0x7FFu, 6);
    b = decodeMagnitude((p >> 22) & 0x3FFu, 5);
}

// VK_FORMAT_E5B9G9R9_UFLOAT_PACK32: 9-bit mantissas R (bits 0..8), G (9..17), B (18..26) and a shared
// exponent (27..31), value = mantissa * 2^(exponent - 15 - 9). Encoding follows the Vulkan spec's
// shared-exponent conversion (as EXT_texture_shared_exponent): the exponent is chosen from the largest
// channel, mantissas are rounded half up. Inputs in [0, kRgb9e5Max].
inline std::uint32_t packE5B9G9R9(float r, float g, float b) {
    constexpr int mantissaBits = 9;
    const float maxChannel = std::max({r, g, b});
    if (!(maxChannel > 0.0f)) return 0;
    int k;
    std::frexp(maxChannel, &k); // maxChannel = f * 2^k with f in [0.5, 1): floor(log2) = k - 1
    int exponent = std::max(-kExponentBias - 1, k - 1) + 1 + kExponentBias;
    // Doubles make the scaled values and the + 0.5 exact.
    double scale = std::ldexp(1.0, -(exponent - kExponentBias - mantissaBits));
    if (std::floor(double(maxChannel) * scale + 0.5) == double(1 << mantissaBits)) {
        ++exponent;
        scale *= 0.5;
    }
    auto mantissa = [&](float c) { return std::uint32_t(std::floor(double(c) * scale + 0.5)); };
    return mantissa(r) | (mantissa(g) << 9) | (mantissa(b) << 18) | (std::uint32_t(exponent) << 27);
}

inline void unpackE5B9G9R9(std::uint32_t p, float& r, float& g, float& b) {
    const int exponent = int(p >> 27) - kExponentBias - 9;
    r = std::ldexp(float(p & 0x1FFu), exponent);
    g = std::ldexp(float((p >> 9) & 0x1FFu), exponent);
    b = std::ldexp(float((p >> 18) & 0x1FFu), exponent);
}

} // namespace ibl::smallfloat
