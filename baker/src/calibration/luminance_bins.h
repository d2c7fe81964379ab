// Luminance bins in the floats' order, for the weighted quantiles of statistics and sun detection: a
// non-negative float's top bits (exponent and 3 mantissa bits) name its bin, so every value of a lower bin
// is smaller than every value of a higher one, and a quantile is found by summing weights per bin and
// sorting the one bin where the running sum crosses the target.
#pragma once

#include <bit>
#include <cstddef>
#include <cstdint>

namespace ibl {

inline constexpr int kLuminanceBinShift = 20;
inline constexpr std::size_t kLuminanceBins = std::size_t(1) << (31 - kLuminanceBinShift);

// Bin of a value; zero and negative values share the lowest bin.
inline std::size_t luminanceBin(float value) {
    return value > 0.0f ? std::size_t(std::bit_cast<std::uint32_t>(value) >> kLuminanceBinShift) : 0;
}

} // namespace ibl
