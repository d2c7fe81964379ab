// The texture of a light card (iblbake/baker/light_card.h): read through the ingest reader, converted to the
// working space with OCIO, repaired, box-resampled to the card's size and normalized to mean luminance 1.
#include "iblbake/baker/light_card.h"
#include "iblbake/core/error.h"

#include "../ingest/ingest_internal.h"

#include <algorithm>
#include <cmath>

namespace ibl {

namespace {

// Area-weighted box resampling along one axis: output texel i of n covers [i, i + 1) n_in / n of the input,
// each input texel weighted by its overlap (exact for up- and downsampling, energy kept).
struct AxisTaps {
    std::vector<std::vector<std::pair<int, double>>> taps; // per output texel: (input texel, weight)
};

AxisTaps axisTaps(int inputSize, int outputSize) {
    AxisTaps a;
    a.taps.resize(std::size_t(outputSize));
    const double scale = double(inputSize) / double(outputSize);
    for (int i = 0; i < outputSize; ++i) {
        const double lo = i * scale, hi = (i + 1) * scale;
        for (int k = int(std::floor(lo)); k < int(std::ceil(hi)) && k < inputSize; ++k) {
            const double overlap = std::min(hi, double(k + 1)) - std::max(lo, double(k));
            if (overlap > 0.0) a.taps[std::size_t(i)].emplace_back(k, overlap / scale);
        }
    }
    return a;
}

ImageRGBA boxResample(const ImageRGBA& in, int size) {
    const AxisTaps tx = axisTaps(in.width, size), ty = axisTaps(in.height, size);
    ImageRGBA out(size, size);
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
            glm::dvec3 sum(0.0);
            for (const auto& [j, wy] : ty.taps[std::size_t(y)])
                for (const auto& [i, wx] : tx.taps[std::size_t(x)])
                    sum += glm::dvec3(glm::vec3(in.at(i, j))) * (wx * wy);
            out.at(x, y) = glm::vec4(glm::vec3(sum), 1.0f);
        }
    return out;
}

} // namespace

LightCardTexture readLightCardTexture(const std::filesystem::path& file, const LightCardSettings& settings,
                                      const std::string& inputColorSpace,
                                      const std::string& workingColorSpace) {
    lightCardLayout(settings, 1.0f); // the settings' ranges, before reading
    ingest::RawImage raw = ingest::readImage(file);
    LightCardTexture texture;
    texture.file = raw.file;
    texture.aspect = float(raw.pixels.width) / float(raw.pixels.height);
    texture.inputColorSpace = ingest::resolveInputColorSpace(raw, inputColorSpace);
    const glm::dvec3 weights = ingest::luminanceWeights(workingColorSpace); // also checks linearity
    texture.workingColorSpace = ingest::colorSpaceName(workingColorSpace);
    ingest::sanitize(raw.pixels);
    ingest::convertColorRepaired(raw.pixels, texture.inputColorSpace, texture.workingColorSpace, raw.file);
    texture.emission = boxResample(raw.pixels, settings.size);
    double sum = 0.0;
    for (const glm::vec4& p : texture.emission.pixels)
        sum += glm::dot(glm::dvec3(glm::vec3(p)), weights);
    texture.sourceMeanLuminance = sum / double(texture.emission.pixels.size());
    if (!(texture.sourceMeanLuminance > 0.0) || !std::isfinite(texture.sourceMeanLuminance))
        throw Error(raw.file + ": the texture emits no light (its mean luminance is " +
                    std::to_string(texture.sourceMeanLuminance) + "), so it cannot be normalized");
    const float scale = float(1.0 / texture.sourceMeanLuminance);
    for (glm::vec4& p : texture.emission.pixels)
        p = glm::vec4(glm::vec3(p) * scale, 1.0f);
    return texture;
}

} // namespace ibl
