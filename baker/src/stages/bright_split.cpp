#include "bright_split.h"
#include "iblbake/core/numeric.h"

#include <bright_list.h>
#include <cube.h>

#include <algorithm>
#include <cmath>

namespace ibl {

std::uint32_t BrightTexels::count() const {
    return std::uint32_t(entries.size() / IBL_BRIGHT_ENTRY_FLOATS);
}
std::uint32_t BrightTexels::clusterCount() const {
    return std::uint32_t(clusters.size() / IBL_BRIGHT_CLUSTER_FLOATS);
}

std::vector<float> brightEntryLanes(const BrightTexels& bright) {
    const std::uint32_t count = bright.count(), stride = brightLaneStride(count);
    std::vector<float> lanes(std::size_t(IBL_BRIGHT_LANE_FLOATS) * stride, 0.0f);
    for (std::uint32_t i = 0; i < count; ++i)
        for (std::uint32_t c = 0; c < IBL_BRIGHT_LANE_FLOATS; ++c)
            lanes[std::size_t(c) * stride + i] = bright.entries[std::size_t(i) * IBL_BRIGHT_ENTRY_FLOATS + c];
    return lanes;
}

namespace {

// Clusters are the bright texels of one 8 x 8 tile of a face: a sun falls into a handful of them.
constexpr int kClusterTile = 8;

void buildClusters(BrightTexels& bright, int faceSize) {
    const std::uint32_t count = bright.count();
    const int tiles = (faceSize + kClusterTile - 1) / kClusterTile;
    auto tileOf = [&](std::uint32_t i) {
        const float* e = &bright.entries[i * IBL_BRIGHT_ENTRY_FLOATS];
        return (int(e[7]) * tiles + int(e[9]) / kClusterTile) * tiles + int(e[8]) / kClusterTile;
    };
    std::vector<std::uint32_t> order(count);
    for (std::uint32_t i = 0; i < count; ++i)
        order[i] = i;
    std::stable_sort(order.begin(), order.end(),
                     [&](std::uint32_t a, std::uint32_t b) { return tileOf(a) < tileOf(b); });
    std::vector<float> sorted;
    sorted.reserve(bright.entries.size());
    for (std::uint32_t i : order)
        sorted.insert(sorted.end(), bright.entries.begin() + i * IBL_BRIGHT_ENTRY_FLOATS,
                      bright.entries.begin() + (i + 1) * IBL_BRIGHT_ENTRY_FLOATS);
    bright.entries = std::move(sorted);
    // A texel's centre is at most about one texel (2 / faceSize radians) from any point of it.
    const float texelAngle = 2.0f / float(faceSize);
    for (std::uint32_t first = 0; first < count;) {
        std::uint32_t end = first;
        const int tile = tileOf(first);
        glm::vec3 centroid(0.0f);
        float energy = 0.0f;
        for (; end < count && tileOf(end) == tile; ++end) {
            const float* e = &bright.entries[end * IBL_BRIGHT_ENTRY_FLOATS];
            float texelEnergy = std::max({e[4], e[5], e[6]}) * e[3];
            centroid += texelEnergy * glm::vec3(e[0], e[1], e[2]);
            energy += texelEnergy;
        }
        centroid = glm::normalize(centroid);
        float radius = 0.0f;
        for (std::uint32_t i = first; i < end; ++i) {
            const float* e = &bright.entries[i * IBL_BRIGHT_ENTRY_FLOATS];
            float c = std::clamp(glm::dot(centroid, glm::vec3(e[0], e[1], e[2])), -1.0f, 1.0f);
            radius = std::max(radius, std::acos(c));
        }
        const float clusterRadius = radius + texelAngle;
        bright.clusters.insert(bright.clusters.end(),
                               {centroid.x, centroid.y, centroid.z, clusterRadius, energy, float(first),
                                float(end - first), std::cos(0.5f * clusterRadius)});
        first = end;
    }
}

} // namespace

BrightChoice chooseBrightTexels(const CubeMap& source, float threshold, std::uint32_t maxTexels) {
    const int n = source.faceSize;
    double weighted = 0.0, totalSolidAngle = 0.0;
    struct Candidate {
        float lum;
        int face, x, y;
    };
    std::vector<Candidate> candidates;
    // Every face has the same texel solid angles: one face's (four atan2 each), not six.
    std::vector<float> solidAngle(std::size_t(n) * std::size_t(n));
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x)
            solidAngle[std::size_t(y) * std::size_t(n) + std::size_t(x)] = cubeTexelSolidAngle(x, y, n);
    for (int f = 0; f < 6; ++f)
        for (int y = 0; y < n; ++y)
            for (int x = 0; x < n; ++x) {
                double omega = solidAngle[std::size_t(y) * std::size_t(n) + std::size_t(x)];
                weighted += rec709Luminance(source.faces[f].at(x, y)) * omega;
                totalSolidAngle += omega;
            }
    const float meanLuminance = float(weighted / totalSolidAngle);
    float limit = threshold * meanLuminance;
    for (int f = 0; f < 6; ++f)
        for (int y = 0; y < n; ++y)
            for (int x = 0; x < n; ++x)
                if (float l = rec709Luminance(source.faces[f].at(x, y)); l > limit && limit > 0.0f)
                    candidates.push_back({l, f, x, y});
    if (candidates.size() > maxTexels) {
        std::nth_element(candidates.begin(), candidates.begin() + maxTexels, candidates.end(),
                         [](const Candidate& a, const Candidate& b) { return a.lum > b.lum; });
        limit = candidates[maxTexels].lum;
        candidates.resize(maxTexels);
    }
    BrightChoice choice;
    choice.thresholdLuminance = limit;
    // What a bright texel leaves in the residual: the map's mean luminance, so that the residual, which
    // filtered importance sampling evaluates at texel centres only, holds almost none of a sun's energy
    // (left at the threshold, 32 x the mean, it held 1.4% of a small sun's, and a level's energy moved by 1%
    // as the sun moved by sub-texel steps). When more texels exceed the threshold than are split off, the
    // threshold itself: the residual then keeps bright texels, and lower ones among them would be holes.
    const float keptLuminance = limit > threshold * meanLuminance ? limit : meanLuminance;
    for (const Candidate& c : candidates)
        choice.texels.push_back({c.face, c.x, c.y, keptLuminance / c.lum});
    return choice;
}

namespace {

// Scales the chosen texels of `cube` down to what they keep and returns their excess (applyBrightSplit).
BrightTexels takeBrightTexels(CubeMap& cube, const BrightChoice& choice) {
    const int n = cube.faceSize;
    BrightTexels bright;
    for (const BrightChoice::Texel& c : choice.texels) {
        glm::vec4& texel = cube.faces[c.face].at(c.x, c.y);
        glm::vec4 kept = texel * c.scale;
        glm::vec3 excess = glm::vec3(texel - kept);
        kept.w = texel.w;
        texel = kept;
        if (excess == glm::vec3(0.0f)) continue; // a companion's transparent texel: nothing to integrate
        vec3 d = glm::normalize(cubeFaceDirection(c.face, (c.x + 0.5f) / n, (c.y + 0.5f) / n));
        bright.entries.insert(bright.entries.end(),
                              {d.x, d.y, d.z,
                               cubePatchSolidAngle(-1.0f + 2.0f * c.x / n, -1.0f + 2.0f * c.y / n, 2.0f / n),
                               excess.x, excess.y, excess.z, float(c.face), float(c.x), float(c.y)});
    }
    buildClusters(bright, n);
    return bright;
}

} // namespace

BrightSplit applyBrightSplit(const CubeMap& cube, const BrightChoice& choice) {
    BrightSplit split;
    split.residual = cube;
    split.thresholdLuminance = choice.thresholdLuminance;
    split.bright = takeBrightTexels(split.residual, choice);
    return split;
}

BrightTexels withResidualInPlace(CubeMap& cube, const BrightChoice& choice,
                                 const std::function<void(const CubeMap& residual)>& useResidual) {
    std::vector<glm::vec4> original;
    original.reserve(choice.texels.size());
    for (const BrightChoice::Texel& c : choice.texels)
        original.push_back(cube.faces[c.face].at(c.x, c.y));
    struct Undo {
        CubeMap& cube;
        const BrightChoice& choice;
        const std::vector<glm::vec4>& original;
        ~Undo() {
            for (std::size_t i = 0; i < choice.texels.size(); ++i)
                cube.faces[choice.texels[i].face].at(choice.texels[i].x, choice.texels[i].y) = original[i];
        }
    } undo{cube, choice, original};
    BrightTexels bright = takeBrightTexels(cube, choice);
    useResidual(cube);
    return bright;
}

BrightSplit splitBrightTexels(const CubeMap& source, float threshold, std::uint32_t maxTexels) {
    return applyBrightSplit(source, chooseBrightTexels(source, threshold, maxTexels));
}

} // namespace ibl
