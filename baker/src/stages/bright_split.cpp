#include "bright_split.h"

#include <cube.h>
#include <ld.h>

#include <algorithm>

namespace ibl {

namespace {
float luminance(const glm::vec4& p) {
    return 0.2126f * p.x + 0.7152f * p.y + 0.0722f * p.z;
}
} // namespace

std::uint32_t BrightTexels::count() const {
    return std::uint32_t(entries.size() / IBL_BRIGHT_ENTRY_FLOATS);
}

BrightSplit splitBrightTexels(const CubeMap& source, float threshold, std::uint32_t maxTexels) {
    const int n = source.faceSize;
    BrightSplit split;
    split.residual = source;

    double weighted = 0.0, totalSolidAngle = 0.0;
    struct Candidate {
        float lum;
        int face, x, y;
    };
    std::vector<Candidate> candidates;
    for (int f = 0; f < 6; ++f)
        for (int y = 0; y < n; ++y)
            for (int x = 0; x < n; ++x) {
                double omega = cubeTexelSolidAngle(x, y, n);
                weighted += luminance(source.faces[f].at(x, y)) * omega;
                totalSolidAngle += omega;
            }
    float limit = float(threshold * weighted / totalSolidAngle);
    for (int f = 0; f < 6; ++f)
        for (int y = 0; y < n; ++y)
            for (int x = 0; x < n; ++x)
                if (float l = luminance(source.faces[f].at(x, y)); l > limit && limit > 0.0f)
                    candidates.push_back({l, f, x, y});
    if (candidates.size() > maxTexels) {
        std::nth_element(candidates.begin(), candidates.begin() + maxTexels, candidates.end(),
                         [](const Candidate& a, const Candidate& b) { return a.lum > b.lum; });
        limit = candidates[maxTexels].lum;
        candidates.resize(maxTexels);
    }
    split.thresholdLuminance = limit;
    for (const Candidate& c : candidates) {
        glm::vec4& texel = split.residual.faces[c.face].at(c.x, c.y);
        glm::vec4 kept = texel * (limit / c.lum);
        glm::vec3 excess = glm::vec3(texel - kept);
        kept.w = texel.w;
        texel = kept;
        vec3 d = glm::normalize(cubeFaceDirection(c.face, (c.x + 0.5f) / n, (c.y + 0.5f) / n));
        split.bright.entries.insert(split.bright.entries.end(),
                                    {d.x, d.y, d.z, cubeTexelSolidAngle(c.x, c.y, n), excess.x, excess.y,
                                     excess.z, float(c.face), float(c.x), float(c.y)});
    }
    return split;
}

} // namespace ibl
