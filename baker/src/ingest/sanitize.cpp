// Repair of pixel values that must not reach the bake (docs/conventions.md "Units and calibration":
// NaN/Inf/negative pixels are repaired and counted, never propagated).
#include "ingest_internal.h"

#include "iblbake/core/visibility.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>

namespace ibl::ingest {

namespace {

// fp16's largest finite value: what +Inf becomes when the image has no finite value to borrow.
constexpr float kHalfMax = 65504.0f;

using Range = tbb::blocked_range<std::size_t>;

float largestFinite(const ImageRGBA& image) {
    return tbb::parallel_reduce(
        Range(0, image.pixels.size(), 4096), -std::numeric_limits<float>::infinity(),
        [&](const Range& r, float m) {
            for (std::size_t i = r.begin(); i != r.end(); ++i)
                for (int c = 0; c < 3; ++c)
                    if (std::isfinite(image.pixels[i][c])) m = std::max(m, image.pixels[i][c]);
            return m;
        },
        [](float a, float b) { return std::max(a, b); });
}

} // namespace

RepairCounts sanitize(ImageRGBA& image) {
    float finiteMax = largestFinite(image);
    // All-negative or empty images have nothing positive to offer; 0 would erase a sun marked as +Inf.
    const float infValue = finiteMax > 0.0f ? finiteMax : kHalfMax;
    return tbb::parallel_reduce(
        Range(0, image.pixels.size(), 4096), RepairCounts{},
        [&](const Range& r, RepairCounts n) {
            for (std::size_t i = r.begin(); i != r.end(); ++i)
                for (int c = 0; c < 3; ++c) {
                    float& v = image.pixels[i][c];
                    if (std::isnan(v)) {
                        v = 0.0f;
                        ++n.nan;
                    } else if (std::isinf(v)) {
                        v = v > 0.0f ? infValue : 0.0f;
                        ++n.inf;
                    } else if (v < 0.0f) {
                        v = 0.0f;
                        ++n.negative;
                    }
                }
            return n;
        },
        std::plus<RepairCounts>());
}

// Alpha is a visibility here: iblbake/core/visibility.h repairs it, as the specular stage does.
AlphaRepairCounts sanitizeAlpha(ImageRGBA& image) {
    return tbb::parallel_reduce(
        Range(0, image.pixels.size(), 4096), AlphaRepairCounts{},
        [&](const Range& r, AlphaRepairCounts n) {
            for (std::size_t i = r.begin(); i != r.end(); ++i) {
                glm::vec4& p = image.pixels[i];
                const VisibilityRepair repair = visibilityRepairOf(p.w);
                n.nan += repair == VisibilityRepair::NaN;
                n.negative += repair == VisibilityRepair::Negative;
                n.overOne += repair == VisibilityRepair::OverOne;
                p = repairedVisibilityTexel(p, repair);
            }
            return n;
        },
        std::plus<AlphaRepairCounts>());
}

bool hasAlphaBelowOne(const ImageRGBA& image) {
    return std::any_of(image.pixels.begin(), image.pixels.end(),
                       [](const glm::vec4& p) { return p.w != 1.0f; });
}

void premultiplyAlpha(ImageRGBA& image) {
    tbb::parallel_for(std::size_t(0), image.pixels.size(), [&](std::size_t i) {
        glm::vec4& p = image.pixels[i];
        p = glm::vec4(glm::vec3(p) * p.w, p.w);
    });
}

namespace {

// Of ImageRGBA or ImageRGBE pixels: decodeRgbe gives the floats decodeKeptRgbe would store.
template <class Pixels, class Decode>
float maxLuminanceOf(const Pixels& pixels, const glm::dvec3& w, Decode decode) {
    return tbb::parallel_reduce(
        Range(0, pixels.size(), 4096), 0.0f,
        [&](const Range& r, float m) {
            for (std::size_t i = r.begin(); i != r.end(); ++i) {
                const glm::vec4 p = decode(pixels[i]);
                m = std::max(m, float(w.x * p.x + w.y * p.y + w.z * p.z));
            }
            return m;
        },
        [](float a, float b) { return std::max(a, b); });
}

} // namespace

FiniteRepair repairFinite(glm::vec4* pixels, std::size_t count, const glm::dvec3& w) {
    FiniteRepair repair;
    RepairCounts& n = repair.counts;
    for (std::size_t i = 0; i < count; ++i) {
        glm::vec4& p = pixels[i];
        for (int c = 0; c < 3; ++c) {
            float& v = p[c];
            if (std::isnan(v)) {
                v = 0.0f;
                ++n.nan;
            } else if (std::isinf(v)) {
                if (v > 0.0f) {
                    ++repair.plusInf;
                    continue;
                }
                v = 0.0f;
                ++n.inf;
            } else if (v < 0.0f) {
                v = 0.0f;
                ++n.negative;
            }
        }
        repair.maxLuminance = std::max(repair.maxLuminance, float(w.x * p.x + w.y * p.y + w.z * p.z));
    }
    return repair;
}

float maxLuminance(const ImageRGBA& image, const glm::dvec3& w) {
    return maxLuminanceOf(image.pixels, w, [](const glm::vec4& p) { return p; });
}

float maxLuminance(const ImageRGBE& image, const glm::dvec3& w) {
    return maxLuminanceOf(image.pixels, w, decodeRgbe);
}

} // namespace ibl::ingest
