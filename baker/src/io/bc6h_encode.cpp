// BC6H (unsigned) encoding. The block's texels are half bit patterns h; a decoder outputs
// finish_unquantize(c) = floor(31 c / 64) of an interpolated 16-bit value c, so the encoder works in that c
// domain (a texel's target is c = (h + 0.5) 64 / 31) and measures error as the squared difference of the
// decoded half patterns from h, each channel weighted by its share of the texel's R + G + B: half patterns
// are nearly logarithmic, so a channel's difference is nearly its relative error, and weighted by its share
// it is nearly that channel's part of the texel's relative error, sum |decoded - v| / sum v
// (docs/formats.md "Format cost").
// For each candidate mode and partition: endpoints from each region's principal axis (extremes of the
// projections), quantized to the mode's precision (a transformed mode's deltas clamped to their range), each
// texel given its nearest palette entry, optionally a least-squares refit of the endpoints to those indices;
// the candidate with the smallest error is packed.
#include "bc6h.h"
#include "bc6h_layout.h"
#include "small_float.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace ibl::bc6h {

namespace {

using Vec3 = std::array<float, 3>;
using Endpoints = std::array<Vec3, 4>; // region 0: 0, 1; region 1: 2, 3 (c domain)

struct Texels {
    BlockHalves halves;
    std::array<Vec3, 16> target; // c domain
    std::array<Vec3, 16> weight; // squared channel weights of the error
};

struct Candidate {
    float error = std::numeric_limits<float>::max();
    Block block{};
    std::array<int, 16> indices{};
};

int quantize(float value, int bits) {
    const int largest = (1 << bits) - 1;
    if (bits >= 15) return std::clamp(int(std::lround(value)), 0, largest);
    const int guess = std::clamp(int(std::lround(value * float(1 << bits) / 65536.0f - 0.5f)), 0, largest);
    int best = guess;
    float bestError = std::fabs(float(unquantize(guess, bits)) - value);
    for (int q : {guess - 1, guess + 1}) {
        if (q < 0 || q > largest) continue;
        const float error = std::fabs(float(unquantize(q, bits)) - value);
        if (error < bestError) {
            best = q;
            bestError = error;
        }
    }
    return best;
}

// The two endpoints of the texels `members` (bit i: texel i) along their principal axis.
void fitLine(const Texels& t, std::uint16_t members, Vec3& low, Vec3& high) {
    Vec3 mean{0, 0, 0};
    int count = 0;
    for (int i = 0; i < kBlockTexels; ++i)
        if (members >> i & 1) {
            for (int c = 0; c < 3; ++c)
                mean[c] += t.target[i][c];
            ++count;
        }
    for (float& m : mean)
        m /= float(count);
    std::array<float, 6> cov{}; // xx, xy, xz, yy, yz, zz
    for (int i = 0; i < kBlockTexels; ++i)
        if (members >> i & 1) {
            const float d0 = t.target[i][0] - mean[0], d1 = t.target[i][1] - mean[1],
                        d2 = t.target[i][2] - mean[2];
            cov[0] += d0 * d0, cov[1] += d0 * d1, cov[2] += d0 * d2;
            cov[3] += d1 * d1, cov[4] += d1 * d2, cov[5] += d2 * d2;
        }
    // Power iteration from the diagonal's largest axis; 8 steps separate the eigenvalues of a block enough.
    Vec3 axis{cov[0] >= cov[3] && cov[0] >= cov[5] ? 1.0f : 0.0f,
              cov[3] > cov[0] && cov[3] >= cov[5] ? 1.0f : 0.0f,
              cov[5] > cov[0] && cov[5] > cov[3] ? 1.0f : 0.0f};
    for (int k = 0; k < 8; ++k) {
        const Vec3 next{cov[0] * axis[0] + cov[1] * axis[1] + cov[2] * axis[2],
                        cov[1] * axis[0] + cov[3] * axis[1] + cov[4] * axis[2],
                        cov[2] * axis[0] + cov[4] * axis[1] + cov[5] * axis[2]};
        const float length = std::sqrt(next[0] * next[0] + next[1] * next[1] + next[2] * next[2]);
        if (!(length > 0.0f)) break;
        for (int c = 0; c < 3; ++c)
            axis[c] = next[c] / length;
    }
    float lowest = 0.0f, highest = 0.0f;
    for (int i = 0; i < kBlockTexels; ++i)
        if (members >> i & 1) {
            float p = 0.0f;
            for (int c = 0; c < 3; ++c)
                p += (t.target[i][c] - mean[c]) * axis[c];
            lowest = std::min(lowest, p);
            highest = std::max(highest, p);
        }
    for (int c = 0; c < 3; ++c) {
        low[c] = std::clamp(mean[c] + lowest * axis[c], 0.0f, 65535.0f);
        high[c] = std::clamp(mean[c] + highest * axis[c], 0.0f, 65535.0f);
    }
}

std::uint16_t regionMembers(int partition, int region) {
    const std::uint16_t ones = kPartitions[std::size_t(partition)];
    return region == 1 ? ones : std::uint16_t(~ones);
}

// One mode and partition with the given endpoints: quantized, indexed, anchors fixed and packed.
Candidate encodeWith(const Texels& t, const Mode& mode, int partition, const Endpoints& endpoints) {
    const int endpointCount = 2 * mode.regions;
    const int largest = (1 << mode.endpointBits) - 1;
    std::array<std::array<int, 3>, 4> q{};
    for (int e = 0; e < endpointCount; ++e)
        for (int c = 0; c < 3; ++c) {
            q[e][c] = quantize(endpoints[e][c], mode.endpointBits);
            if (mode.transformed && e > 0) {
                const int reach = 1 << (mode.deltaBits[c] - 1);
                q[e][c] =
                    std::clamp(q[e][c], std::max(0, q[0][c] - reach), std::min(largest, q[0][c] + reach - 1));
            }
        }
    const int indexBits = mode.regions == 2 ? 3 : 4;
    const int paletteSize = 1 << indexBits;
    const int* weights = indexBits == 3 ? kWeights3.data() : kWeights4.data();
    std::array<std::array<std::array<int, 3>, 16>, 2> palette{};
    for (int r = 0; r < mode.regions; ++r)
        for (int k = 0; k < paletteSize; ++k)
            for (int c = 0; c < 3; ++c)
                palette[r][k][c] =
                    finishUnquantize(interpolate(unquantize(q[2 * r][c], mode.endpointBits),
                                                 unquantize(q[2 * r + 1][c], mode.endpointBits), weights[k]));
    Candidate out;
    out.error = 0;
    std::array<int, 16> region{};
    for (int i = 0; i < kBlockTexels; ++i) {
        region[i] = mode.regions == 2 ? regionOf(partition, i) : 0;
        float best = std::numeric_limits<float>::max();
        for (int k = 0; k < paletteSize; ++k) {
            float error = 0;
            for (int c = 0; c < 3; ++c) {
                const float d = float(palette[region[i]][k][c] - t.halves[i][c]);
                error += d * d * t.weight[i][c];
            }
            if (error < best) {
                best = error;
                out.indices[i] = k;
            }
        }
        out.error += best;
    }
    // An anchor's index has no top bit: where it would be set, swap the region's endpoints and mirror its
    // indices (the weights are symmetric, so the texels decode the same). A transformed mode swaps region 0
    // only when every delta still fits from the new base; otherwise the anchor takes the nearest allowed
    // index.
    const std::array<int, 2> anchors = {0, mode.regions == 2 ? int(kAnchor2[std::size_t(partition)]) : 0};
    for (int r = 0; r < mode.regions; ++r) {
        const int anchor = anchors[r];
        if (out.indices[anchor] < paletteSize / 2) continue;
        bool swappable = true;
        if (mode.transformed && r == 0)
            for (int e = 1; e < endpointCount; ++e)
                for (int c = 0; c < 3; ++c) {
                    const int reach = 1 << (mode.deltaBits[c] - 1);
                    const int d = (e == 1 ? q[0][c] : q[e][c]) - q[1][c];
                    swappable = swappable && d >= -reach && d < reach;
                }
        if (swappable) {
            std::swap(q[2 * r], q[2 * r + 1]);
            for (int i = 0; i < kBlockTexels; ++i)
                if (region[i] == r) out.indices[i] = paletteSize - 1 - out.indices[i];
        } else {
            const int forced = paletteSize / 2 - 1;
            for (int c = 0; c < 3; ++c) {
                const float was = float(palette[r][out.indices[anchor]][c] - t.halves[anchor][c]);
                const float now = float(palette[r][forced][c] - t.halves[anchor][c]);
                out.error += (now * now - was * was) * t.weight[anchor][c];
            }
            out.indices[anchor] = forced;
        }
    }

    Bits128 bits;
    int position = 0;
    for (int b = 0; b < mode.modeBits; ++b)
        bits.set(position++, mode.code >> b & 1);
    std::array<int, 12> field{};
    for (int e = 0; e < endpointCount; ++e)
        for (int c = 0; c < 3; ++c)
            field[fieldOf(e, c)] =
                mode.transformed && e > 0 ? (q[e][c] - q[0][c]) & ((1 << mode.deltaBits[c]) - 1) : q[e][c];
    for (const BitRun& r : mode.runs) {
        if (isEnd(r)) break;
        const int step = r.first <= r.last ? 1 : -1;
        for (int b = r.first;; b += step) {
            bits.set(position++, field[r.field] >> b & 1);
            if (b == r.last) break;
        }
    }
    if (mode.regions == 2)
        for (int b = 0; b < 5; ++b)
            bits.set(position++, partition >> b & 1);
    for (int i = 0; i < kBlockTexels; ++i) {
        const bool anchor = i == anchors[0] || (mode.regions == 2 && i == anchors[1]);
        for (int b = 0; b < indexBits - (anchor ? 1 : 0); ++b)
            bits.set(position++, out.indices[i] >> b & 1);
    }
    for (int i = 0; i < kBlockBytes; ++i)
        out.block[i] = std::uint8_t(bits.word[i / 8] >> (8 * (i % 8)));
    return out;
}

// Least-squares endpoints for the indices of `c` (per region, per channel: minimize the squared distance
// of (1 - a) e0 + a e1 to the targets, a = weight / 64); a region whose indices are all equal keeps its own.
Endpoints refit(const Texels& t, const Mode& mode, int partition, const Candidate& c, Endpoints endpoints) {
    const int* weights = mode.regions == 2 ? kWeights3.data() : kWeights4.data();
    for (int r = 0; r < mode.regions; ++r) {
        double aa = 0, ab = 0, bb = 0;
        std::array<double, 3> at{}, bt{};
        for (int i = 0; i < kBlockTexels; ++i) {
            if ((mode.regions == 2 ? regionOf(partition, i) : 0) != r) continue;
            const double b = weights[c.indices[i]] / 64.0, a = 1.0 - b;
            aa += a * a, ab += a * b, bb += b * b;
            for (int ch = 0; ch < 3; ++ch) {
                at[ch] += a * t.target[i][ch];
                bt[ch] += b * t.target[i][ch];
            }
        }
        const double det = aa * bb - ab * ab;
        if (std::fabs(det) < 1e-9) continue;
        for (int ch = 0; ch < 3; ++ch) {
            endpoints[2 * r][ch] = float(std::clamp((at[ch] * bb - bt[ch] * ab) / det, 0.0, 65535.0));
            endpoints[2 * r + 1][ch] = float(std::clamp((bt[ch] * aa - at[ch] * ab) / det, 0.0, 65535.0));
        }
    }
    return endpoints;
}

// A texel set's spread: the sum of squared distances from its mean (c domain).
float spread(const Texels& t, std::uint16_t members) {
    Vec3 sum{0, 0, 0};
    float squares = 0.0f;
    int count = 0;
    for (int i = 0; i < kBlockTexels; ++i)
        if (members >> i & 1) {
            for (int c = 0; c < 3; ++c) {
                sum[c] += t.target[i][c];
                squares += t.target[i][c] * t.target[i][c];
            }
            ++count;
        }
    return count == 0 ? 0.0f : squares - (sum[0] * sum[0] + sum[1] * sum[1] + sum[2] * sum[2]) / float(count);
}

struct Trial {
    const Mode* mode = nullptr;
    int partition = 0;
    Endpoints endpoints{};
    Candidate candidate;
};

void consider(const Texels& t, const Mode& mode, int partition, const Endpoints& endpoints, Trial& best) {
    Candidate c = encodeWith(t, mode, partition, endpoints);
    if (c.error < best.candidate.error) best = {&mode, partition, endpoints, c};
}

// Least-squares refits of the trial's endpoints while they lower its error.
void refine(const Texels& t, int refits, Trial& trial) {
    for (int k = 0; k < refits && trial.candidate.error > 0; ++k) {
        const Endpoints endpoints = refit(t, *trial.mode, trial.partition, trial.candidate, trial.endpoints);
        const Candidate next = encodeWith(t, *trial.mode, trial.partition, endpoints);
        if (next.error >= trial.candidate.error) break;
        trial.endpoints = endpoints;
        trial.candidate = next;
    }
}

} // namespace

Block encodeBlock(const BlockHalves& halves, Preset preset) {
    Texels t;
    t.halves = halves;
    for (int i = 0; i < kBlockTexels; ++i) {
        Vec3 value;
        for (int c = 0; c < 3; ++c) {
            t.target[i][c] = (float(halves[i][c]) + 0.5f) * (64.0f / 31.0f);
            value[c] = smallfloat::halfToFloat(halves[i][c]);
        }
        // A channel's share of R + G + B, at least 5%: a nearly black channel still keeps its order of size.
        const float sum = value[0] + value[1] + value[2];
        for (int c = 0; c < 3; ++c) {
            const float share = sum > 0.0f ? std::max(value[c] / sum, 0.05f) : 1.0f / 3.0f;
            t.weight[i][c] = share * share;
        }
    }

    // One region: mode 11 (fast), or every one-region mode, the best refined.
    const int refits = preset == Preset::Fast ? 0 : preset == Preset::Default ? 1 : 3;
    Endpoints single{};
    fitLine(t, 0xFFFF, single[0], single[1]);
    Trial best;
    for (const Mode& mode : kModes)
        if (mode.regions == 1 && (preset != Preset::Fast || mode.number == 11))
            consider(t, mode, 0, single, best);
    refine(t, refits, best);
    // Default stops where one region is already within about 0.5% (a weighted squared half difference of
    // 16 a texel): on potsdamer_platz_1k's chain that halves the time (2.2 -> 1.1 s) for a mean error 0.905
    // -> 0.906% at level 0 (docs/formats.md "BC6H").
    const float goodEnough = preset == Preset::Default ? 16.0f * kBlockTexels : 0.0f;
    if (preset == Preset::Fast || best.candidate.error <= goodEnough) return best.candidate.block;

    // Two regions: the partitions whose regions are most compact, best first, in every two-region mode.
    std::array<std::pair<float, int>, 32> ranked;
    for (int p = 0; p < 32; ++p)
        ranked[p] = {spread(t, regionMembers(p, 0)) + spread(t, regionMembers(p, 1)), p};
    const int tried = preset == Preset::Default ? 2 : 8;
    std::partial_sort(ranked.begin(), ranked.begin() + tried, ranked.end());
    Trial two;
    for (int k = 0; k < tried; ++k) {
        const int p = ranked[k].second;
        Endpoints fitted{};
        fitLine(t, regionMembers(p, 0), fitted[0], fitted[1]);
        fitLine(t, regionMembers(p, 1), fitted[2], fitted[3]);
        for (const Mode& mode : kModes) {
            if (mode.regions != 2) continue;
            if (preset == Preset::Best) { // every mode refined, not only the best one
                Trial trial;
                consider(t, mode, p, fitted, trial);
                refine(t, refits, trial);
                if (trial.candidate.error < two.candidate.error) two = trial;
            } else {
                consider(t, mode, p, fitted, two);
            }
        }
    }
    if (preset == Preset::Default) refine(t, refits, two);
    return two.candidate.error < best.candidate.error ? two.candidate.block : best.candidate.block;
}

void encodeImage(const ImageRGBA& image, Preset preset, std::uint8_t* out) {
    const int blocksX = (image.width + 3) / 4, blocksY = (image.height + 3) / 4;
    tbb::parallel_for(0, blocksY, [&](int by) {
        for (int bx = 0; bx < blocksX; ++bx) {
            BlockHalves halves;
            for (int i = 0; i < kBlockTexels; ++i) {
                // Texels past the image's edge repeat the nearest edge texel (levels of 2 x 2 and 1 x 1).
                const int x = std::min(4 * bx + i % 4, image.width - 1);
                const int y = std::min(4 * by + i / 4, image.height - 1);
                const glm::vec4& texel = image.at(x, y);
                for (int c = 0; c < 3; ++c)
                    halves[i][c] = smallfloat::floatToHalf(texel[c]);
            }
            const Block block = encodeBlock(halves, preset);
            std::copy(block.begin(), block.end(),
                      out + kBlockBytes * (std::size_t(by) * std::size_t(blocksX) + std::size_t(bx)));
        }
    });
}

} // namespace ibl::bc6h
