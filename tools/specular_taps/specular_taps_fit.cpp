#include "specular_taps_fit.h"

#include "mip_mapping.h"
#include "probe.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>

namespace ibl::taps {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr int kCoefficientCount = (kMaxBand + 1) * (kMaxBand + 2) / 2; // m = 0..l per band
// Stratified GGX samples of the half vector per axis for the lobe's coefficients, and samples of the level
// kernels' Legendre moments.
constexpr int kLobeSamplesPerAxis = 160;
constexpr int kKernelSamples = 20000;

// Band powers of the environments the match is for: natural lighting's power per coefficient falls about as
// 1 / l^2. Measured on the shared HDRIs (docs/accuracy.md "Every shared HDRI"): weights 1 / (l + 1) were up
// to 0.5 points worse at r = 0.4-0.5, and bands up to 48 instead of 32 up to 0.7 points worse at r = 0.3.
double bandWeight(int l) {
    return 1.0 / (double(l + 1) * double(l + 1));
}

// Bounds of a tap: the lerp factor from -0.5 (past N, away from R: rough lobes at grazing views are wide
// about N) to 1 (R); the lookup roughness at least 0.4 r (lower ones read levels whose texels are wider than
// their lobes, and at r < 0.04 level 0, which keeps an extracted sun's pixels).
constexpr double kMinLerpFactor = -0.5;
constexpr double kMinRoughnessRatio = 0.4;

int coefficientIndex(int l, int m) {
    return l * (l + 1) / 2 + m;
}

// Real orthonormal SH, cos(m phi) terms only, at (cosTheta, phi); out has kCoefficientCount entries.
void evalShCos(double cosTheta, double phi, double* out) {
    const double sinTheta = std::sqrt(std::max(0.0, 1.0 - cosTheta * cosTheta));
    double pmm = std::sqrt(1.0 / (4.0 * kPi)); // normalized P_m^m
    for (int m = 0; m <= kMaxBand; ++m) {
        if (m > 0) pmm *= -std::sqrt((2.0 * m + 1.0) / (2.0 * m)) * sinTheta;
        const double azimuth = m == 0 ? 1.0 : std::sqrt(2.0) * std::cos(m * phi);
        double p2 = pmm, p1 = 0.0;
        out[coefficientIndex(m, m)] = pmm * azimuth;
        if (m == kMaxBand) break;
        p1 = std::sqrt(2.0 * m + 3.0) * cosTheta * pmm;
        out[coefficientIndex(m + 1, m)] = p1 * azimuth;
        for (int l = m + 2; l <= kMaxBand; ++l) {
            const double a = std::sqrt((4.0 * l * l - 1.0) / (double(l) * l - double(m) * m));
            const double b =
                std::sqrt((double(l - 1) * (l - 1) - double(m) * m) / (4.0 * (l - 1) * (l - 1) - 1.0));
            const double p = a * (cosTheta * p1 - b * p2);
            out[coefficientIndex(l, m)] = p * azimuth;
            p2 = p1;
            p1 = p;
        }
    }
}

double smithCorrelatedV(double NoV, double NoL, double alpha) {
    const double a2 = alpha * alpha;
    const double gv = NoL * std::sqrt(NoV * NoV * (1.0 - a2) + a2);
    const double gl = NoV * std::sqrt(NoL * NoL * (1.0 - a2) + a2);
    return 0.5 / (gv + gl);
}

// cos(theta_h) of GGX's CDF at u (sampling D(h) <n.h>).
double ggxCosThetaH(double u, double alpha) {
    return std::sqrt((1.0 - u) / (1.0 + (alpha * alpha - 1.0) * u));
}

// Legendre moments lambda_l = E[P_l(mu)] of the N = V = R level kernel D(h) <n.l> at perceptual roughness r
// (mu = n.l); lambda_l = 1 for r = 0 (level 0: the source itself).
std::array<double, kMaxBand + 1> levelKernelMoments(double perceptualRoughness) {
    std::array<double, kMaxBand + 1> lambda{};
    lambda.fill(1.0);
    if (perceptualRoughness <= 0.0) return lambda;
    const double alpha = perceptualRoughness * perceptualRoughness;
    std::array<double, kMaxBand + 1> sum{};
    double total = 0.0;
    // Samples of h with density D <n.h> (the u of GGX's CDF): l = reflect about h has density D <n.h> / (4
    // <v.h>), so the kernel's weight per sample is <n.l> (the 4 <v.h> = 4 <n.h> Jacobian cancels the
    // density's).
    for (int s = 0; s < kKernelSamples; ++s) {
        const double c = ggxCosThetaH((s + 0.5) / kKernelSamples, alpha);
        const double mu = 2.0 * c * c - 1.0;
        if (mu <= 0.0) continue;
        double p0 = 1.0, p1 = mu;
        sum[0] += mu;
        sum[1] += mu * mu;
        for (int l = 2; l <= kMaxBand; ++l) {
            const double p = ((2.0 * l - 1.0) * mu * p1 - (l - 1.0) * p0) / l;
            sum[std::size_t(l)] += mu * p;
            p0 = p1;
            p1 = p;
        }
        total += mu;
    }
    for (int l = 0; l <= kMaxBand; ++l)
        lambda[std::size_t(l)] = sum[std::size_t(l)] / total;
    return lambda;
}

// The moments of what the runtime reads at perceptual roughness r: the chain's two levels around r's LOD,
// linear between, and the rough layers likewise, blended as sampleLdWithLayers blends them.
struct ChainKernels {
    std::array<std::array<double, kMaxBand + 1>, kChainLevels> levels;
    std::array<std::array<double, kMaxBand + 1>, IBL_ROUGH_LAYER_COUNT> layers;
    ChainKernels() {
        for (int m = 0; m < kChainLevels; ++m)
            levels[std::size_t(m)] =
                levelKernelMoments(mipLevelRoughness(IBL_MIP_FROSTBITE, uint32_t(m), uint32_t(kChainLevels)));
        for (uint32_t k = 0; k < IBL_ROUGH_LAYER_COUNT; ++k)
            layers[k] = levelKernelMoments(roughLayerRoughness(k));
    }
    std::array<double, kMaxBand + 1> lookup(double perceptualRoughness) const {
        const float r = float(std::clamp(perceptualRoughness, 0.0, 1.0));
        const double lod = mipLevelForRoughness(IBL_MIP_FROSTBITE, r, uint32_t(kChainLevels));
        const int m = std::min(int(lod), kChainLevels - 1), m1 = std::min(m + 1, kChainLevels - 1);
        const double f = lod - m;
        const double layerWeight = roughLayerWeight(r);
        const double t =
            std::clamp(double(roughLayerForRoughness(r)), 0.0, double(IBL_ROUGH_LAYER_COUNT - 1));
        const int k = std::min(int(t), int(IBL_ROUGH_LAYER_COUNT) - 1);
        const int k1 = std::min(k + 1, int(IBL_ROUGH_LAYER_COUNT) - 1);
        const double g = t - k;
        std::array<double, kMaxBand + 1> out{};
        for (std::size_t l = 0; l <= kMaxBand; ++l) {
            const double chain = (1.0 - f) * levels[std::size_t(m)][l] + f * levels[std::size_t(m1)][l];
            const double layer = (1.0 - g) * layers[std::size_t(k)][l] + g * layers[std::size_t(k1)][l];
            out[l] = (1.0 - layerWeight) * chain + layerWeight * layer;
        }
        return out;
    }
};

const ChainKernels& chainKernels() {
    static const ChainKernels kernels;
    return kernels;
}

// The tap's direction in the frame N = +z, R = (-sin, 0, cos).
void tapDirection(double NoV, double lerpFactor, double& cosTheta, double& phi) {
    const double sinV = std::sqrt(std::max(0.0, 1.0 - NoV * NoV));
    const double x = -lerpFactor * sinV, z = 1.0 - lerpFactor + lerpFactor * NoV;
    const double length = std::hypot(x, z);
    cosTheta = length > 0.0 ? z / length : 1.0;
    phi = x < 0.0 ? kPi : 0.0;
}

double weightedNorm(const std::vector<double>& c) {
    double sum = 0.0;
    for (int l = 0; l <= kMaxBand; ++l)
        for (int m = 0; m <= l; ++m)
            sum += bandWeight(l) * c[std::size_t(coefficientIndex(l, m))] *
                   c[std::size_t(coefficientIndex(l, m))];
    return sum;
}

// Nelder-Mead over x (bounds are the objective's business), to a relative tolerance.
std::vector<double> nelderMead(const std::function<double(const std::vector<double>&)>& f,
                               std::vector<double> x0, double step, int maxEvaluations) {
    const std::size_t n = x0.size();
    std::vector<std::vector<double>> simplex(n + 1, x0);
    std::vector<double> value(n + 1);
    for (std::size_t i = 0; i < n; ++i)
        simplex[i + 1][i] += step;
    for (std::size_t i = 0; i <= n; ++i)
        value[i] = f(simplex[i]);
    int evaluations = int(n + 1);
    while (evaluations < maxEvaluations) {
        std::vector<std::size_t> order(n + 1);
        for (std::size_t i = 0; i <= n; ++i)
            order[i] = i;
        std::sort(order.begin(), order.end(),
                  [&](std::size_t a, std::size_t b) { return value[a] < value[b]; });
        const std::size_t best = order[0], worst = order[n], second = order[n - 1];
        if (value[worst] - value[best] <= 1e-10 * (std::abs(value[best]) + 1e-12)) break;
        std::vector<double> centroid(n, 0.0);
        for (std::size_t i = 0; i <= n; ++i)
            if (i != worst)
                for (std::size_t k = 0; k < n; ++k)
                    centroid[k] += simplex[i][k] / double(n);
        auto along = [&](double t) {
            std::vector<double> x(n);
            for (std::size_t k = 0; k < n; ++k)
                x[k] = centroid[k] + t * (simplex[worst][k] - centroid[k]);
            return x;
        };
        std::vector<double> reflected = along(-1.0);
        const double fr = f(reflected);
        ++evaluations;
        if (fr < value[best]) {
            std::vector<double> expanded = along(-2.0);
            const double fe = f(expanded);
            ++evaluations;
            if (fe < fr)
                simplex[worst] = expanded, value[worst] = fe;
            else
                simplex[worst] = reflected, value[worst] = fr;
        } else if (fr < value[second]) {
            simplex[worst] = reflected, value[worst] = fr;
        } else {
            std::vector<double> contracted = along(fr < value[worst] ? -0.5 : 0.5);
            const double fc = f(contracted);
            ++evaluations;
            if (fc < std::min(fr, value[worst])) {
                simplex[worst] = contracted, value[worst] = fc;
            } else { // shrink toward the best
                for (std::size_t i = 0; i <= n; ++i)
                    if (i != best) {
                        for (std::size_t k = 0; k < n; ++k)
                            simplex[i][k] = simplex[best][k] + 0.5 * (simplex[i][k] - simplex[best][k]);
                        value[i] = f(simplex[i]);
                        ++evaluations;
                    }
            }
        }
    }
    return simplex[std::size_t(std::min_element(value.begin(), value.end()) - value.begin())];
}

// Parameters: per tap the lerp factor and the roughness over r (r = 0: the roughness itself), then tapCount
// - 1 weight logits (the last tap's logit is 0).
void unpack(const std::vector<double>& x, double perceptualRoughness, int tapCount, Tap* taps) {
    double logits[kMaxTaps] = {0.0, 0.0, 0.0}, maxLogit = 0.0, sum = 0.0;
    for (int k = 0; k + 1 < tapCount; ++k)
        logits[k] = x[std::size_t(2 * tapCount + k)], maxLogit = std::max(maxLogit, logits[k]);
    for (int k = 0; k < tapCount; ++k)
        sum += std::exp(logits[k] - maxLogit);
    for (int k = 0; k < tapCount; ++k) {
        taps[k].lerpFactor = std::clamp(x[std::size_t(k)], kMinLerpFactor, 1.0);
        taps[k].roughness = std::clamp(x[std::size_t(tapCount + k)] * perceptualRoughness,
                                       std::min(1.0, kMinRoughnessRatio * perceptualRoughness), 1.0);
        taps[k].weight = std::exp(logits[k] - maxLogit) / sum;
    }
}

double boundsPenalty(const std::vector<double>& x, double perceptualRoughness, int tapCount) {
    double penalty = 0.0;
    for (int k = 0; k < tapCount; ++k) {
        const double t = x[std::size_t(k)], q = x[std::size_t(tapCount + k)] * perceptualRoughness;
        penalty += std::pow(std::max(0.0, kMinLerpFactor - t), 2) + std::pow(std::max(0.0, t - 1.0), 2);
        penalty += std::pow(std::max(0.0, std::min(1.0, kMinRoughnessRatio * perceptualRoughness) - q), 2) +
                   std::pow(std::max(0.0, q - 1.0), 2);
    }
    for (int k = 0; k + 1 < tapCount; ++k)
        penalty += std::pow(std::max(0.0, std::abs(x[std::size_t(2 * tapCount + k)]) - 8.0), 2);
    return penalty;
}

} // namespace

double cellNoV(int i) {
    return std::max(kMinNoV, double(i) / double(kGridSize - 1));
}

double cellRoughness(int j) {
    return double(j) / double(kGridSize - 1);
}

std::vector<double> lobeCoefficients(double NoV, double perceptualRoughness) {
    std::vector<double> c(kCoefficientCount, 0.0);
    const double alpha = std::max(perceptualRoughness * perceptualRoughness, 1e-4);
    const double sinV = std::sqrt(std::max(0.0, 1.0 - NoV * NoV));
    const double vx = sinV, vz = NoV;
    std::vector<double> y(kCoefficientCount);
    double total = 0.0;
    for (int a = 0; a < kLobeSamplesPerAxis; ++a) {
        const double cosH = ggxCosThetaH((a + 0.5) / kLobeSamplesPerAxis, alpha);
        const double sinH = std::sqrt(std::max(0.0, 1.0 - cosH * cosH));
        for (int b = 0; b < kLobeSamplesPerAxis; ++b) {
            const double phiH = 2.0 * kPi * (b + 0.5) / kLobeSamplesPerAxis;
            const double hx = sinH * std::cos(phiH), hy = sinH * std::sin(phiH), hz = cosH;
            const double VoH = vx * hx + vz * hz;
            if (VoH <= 0.0) continue;
            const double lx = 2.0 * VoH * hx - vx, ly = 2.0 * VoH * hy, lz = 2.0 * VoH * hz - vz;
            if (lz <= 0.0) continue;
            // f <n.l> / pdf(l), pdf(l) = D <n.h> / (4 <v.h>), F = 1
            const double weight = smithCorrelatedV(NoV, lz, alpha) * lz * 4.0 * VoH / cosH;
            evalShCos(std::clamp(lz, -1.0, 1.0), std::atan2(ly, lx), y.data());
            for (int i = 0; i < kCoefficientCount; ++i)
                c[std::size_t(i)] += weight * y[std::size_t(i)];
            total += weight;
        }
    }
    for (double& v : c)
        v /= total;
    return c;
}

double tapsResidual(const std::vector<double>& lobe, double NoV, const Tap* taps, int tapCount) {
    std::vector<double> model(kCoefficientCount, 0.0), y(kCoefficientCount);
    for (int k = 0; k < tapCount; ++k) {
        double cosTheta = 1.0, phi = 0.0;
        tapDirection(NoV, taps[k].lerpFactor, cosTheta, phi);
        evalShCos(cosTheta, phi, y.data());
        const std::array<double, kMaxBand + 1> lambda = chainKernels().lookup(taps[k].roughness);
        for (int l = 0; l <= kMaxBand; ++l)
            for (int m = 0; m <= l; ++m) {
                const std::size_t i = std::size_t(coefficientIndex(l, m));
                model[i] += taps[k].weight * lambda[std::size_t(l)] * y[i];
            }
    }
    for (std::size_t i = 0; i < model.size(); ++i)
        model[i] -= lobe[i];
    return std::sqrt(weightedNorm(model) / weightedNorm(lobe));
}

CellFit fitCell(const std::vector<double>& lobe, double NoV, double perceptualRoughness, int tapCount,
                const CellFit* start) {
    const double r = std::max(perceptualRoughness, 1e-3);
    auto objective = [&](const std::vector<double>& x) {
        Tap taps[kMaxTaps];
        unpack(x, r, tapCount, taps);
        return tapsResidual(lobe, NoV, taps, tapCount) + boundsPenalty(x, r, tapCount);
    };
    auto pack = [&](const CellFit& fit) {
        std::vector<double> x(std::size_t(3 * tapCount - 1), 0.0);
        for (int k = 0; k < tapCount; ++k) {
            const Tap& t = fit.taps[std::size_t(std::min(k, fit.tapCount - 1))];
            x[std::size_t(k)] = t.lerpFactor;
            x[std::size_t(tapCount + k)] = t.roughness / r;
        }
        const double last = std::max(fit.taps[std::size_t(fit.tapCount - 1)].weight, 1e-4);
        for (int k = 0; k + 1 < tapCount; ++k)
            x[std::size_t(2 * tapCount + k)] =
                k < fit.tapCount - 1 ? std::log(std::max(fit.taps[std::size_t(k)].weight, 1e-4) / last)
                                     : -3.0;
        return x;
    };
    std::vector<std::vector<double>> starts;
    if (start != nullptr)
        starts.push_back(pack(*start));
    else {
        const CellFit split = splitSumCell(NoV, perceptualRoughness);
        const double t = split.taps[0].lerpFactor;
        for (double spread : {0.15, 0.4}) {
            CellFit generic;
            generic.tapCount = tapCount;
            for (int k = 0; k < tapCount; ++k) {
                const double offset = tapCount == 1 ? 0.0 : spread * (double(k) / (tapCount - 1) - 0.5);
                generic.taps[std::size_t(k)] = {std::clamp(t + offset, 0.0, 1.0), perceptualRoughness,
                                                1.0 / tapCount};
            }
            starts.push_back(pack(generic));
        }
    }
    CellFit best;
    best.residual = 1e300;
    for (std::vector<double> x : starts) {
        for (int round = 0; round < 3; ++round) // restarts from the last minimum: Nelder-Mead stalls
            x = nelderMead(objective, x, round == 0 ? 0.1 : 0.03, 4000);
        CellFit fit;
        fit.tapCount = tapCount;
        unpack(x, r, tapCount, fit.taps.data());
        for (std::size_t a = 1; a < std::size_t(tapCount) && a < fit.taps.size(); ++a) // by lerp factor
            for (std::size_t b = a; b > 0 && fit.taps[b].lerpFactor < fit.taps[b - 1].lerpFactor; --b)
                std::swap(fit.taps[b], fit.taps[b - 1]);
        fit.residual = tapsResidual(lobe, NoV, fit.taps.data(), tapCount);
        if (fit.residual < best.residual) best = fit;
    }
    return best;
}

CellFit splitSumCell(double NoV, double perceptualRoughness) {
    const float r = float(perceptualRoughness);
    CellFit fit;
    fit.tapCount = 1;
    fit.taps[0] = {0.5 * (specularDominantLerpListing22(r * r) + specularLobeMeanLerp(float(NoV), r)),
                   perceptualRoughness, 1.0};
    return fit;
}

std::vector<CellFit> fitTable(int tapCount) {
    std::vector<CellFit> table(std::size_t(kGridSize * kGridSize));
    for (int j = 0; j < kGridSize; ++j) {
        const double r = cellRoughness(j);
        for (int i = kGridSize - 1; i >= 0; --i) {
            CellFit& cell = table[std::size_t(j * kGridSize + i)];
            const double NoV = cellNoV(i);
            if (j == 0) { // a mirror: every tap at R, r = 0
                cell.tapCount = tapCount;
                for (int k = 0; k < tapCount; ++k)
                    cell.taps[std::size_t(k)] = {1.0, 0.0, 1.0 / tapCount};
                continue;
            }
            const std::vector<double> lobe = lobeCoefficients(NoV, r);
            const CellFit* start = i + 1 < kGridSize
                                       ? &table[std::size_t(j * kGridSize + i + 1)]
                                       : (j > 1 ? &table[std::size_t((j - 1) * kGridSize + i)] : nullptr);
            cell = fitCell(lobe, NoV, r, tapCount, start);
            // A fresh start where the continuation stalled well above it.
            const CellFit fresh = fitCell(lobe, NoV, r, tapCount, nullptr);
            if (fresh.residual < 0.97 * cell.residual) cell = fresh;
            std::fprintf(stderr, "cell NoV %.3f r %.3f: residual %.4f (split sum %.4f)\n", NoV, r,
                         cell.residual, tapsResidual(lobe, NoV, splitSumCell(NoV, r).taps.data(), 1));
        }
    }
    return table;
}

std::string tableHeaderText(const std::vector<CellFit>& table, int tapCount) {
    const int floatsPerCell = 3 * tapCount;
    const std::size_t count = table.size() * std::size_t(floatsPerCell);
    std::string text;
    char line[256];
    auto add = [&](const char* s) { text += s; };
    add("// The runtime's multi-tap specular lookup (kernels/probe.h specularTaps): generated by\n"
        "// `cmake --build build --target specular-taps-table` (tools/specular_taps), do not edit.\n"
        "// Cell (i, j) of the grid holds NoV = i / (IBL_SPECULAR_TAP_GRID - 1), perceptual roughness r = j "
        "/\n"
        "// (IBL_SPECULAR_TAP_GRID - 1); per tap 3 floats: the lerp factor t (direction normalize(lerp(N, R, "
        "t))),\n"
        "// the lookup roughness over r (1 on the r = 0 row), the weight (the taps' weights sum to 1). "
        "Fitted in\n"
        "// fp64 against the normalized GGX lobe f(v, l) <n.l> (height-correlated Smith, F = 1) in SH bands "
        "0-32\n"
        "// (band weight 1 / (l + 1)^2), each tap being what a 256-px Frostbite chain with rough layers "
        "holds there.\n"
        "#ifndef IBL_SPECULAR_TAPS_TABLE_H\n#define IBL_SPECULAR_TAPS_TABLE_H\n\n#include "
        "\"portable.h\"\n\n");
    std::snprintf(line, sizeof line,
                  "#define IBL_SPECULAR_TAP_COUNT %du\n#define IBL_SPECULAR_TAP_GRID %du\n\n", tapCount,
                  kGridSize);
    add(line);
    add("IBL_BEGIN_NAMESPACE\n\n");
    std::snprintf(line, sizeof line,
                  "#if defined(IBL_GLSL)\nconst float kSpecularTapTable[%zu] = float[%zu](\n#elif "
                  "defined(__OPENCL_VERSION__)\n__constant float kSpecularTapTable[%zu] = {\n#else\ninline "
                  "constexpr float kSpecularTapTable[%zu] = {\n#endif\n",
                  count, count, count, count);
    add(line);
    for (std::size_t c = 0; c < table.size(); ++c) {
        const CellFit& cell = table[c];
        const double r = cellRoughness(int(c) / kGridSize);
        text += "    ";
        for (int k = 0; k < tapCount; ++k) {
            const Tap& t = cell.taps[std::size_t(k)];
            const double ratio = r > 0.0 ? t.roughness / r : 1.0;
            const bool last = c + 1 == table.size() && k + 1 == tapCount;
            std::snprintf(line, sizeof line, "%.6ff, %.6ff, %.6ff%s", t.lerpFactor, ratio, t.weight,
                          last ? "" : ", ");
            text += line;
        }
        text += "\n";
    }
    add("#if defined(IBL_GLSL)\n);\n#else\n};\n#endif\n\n");
    add("#ifdef __cplusplus\n// Each cell's relative band-limited error (tools/specular_taps tapsResidual), "
        "for the check that the table\n"
        "// and the program agree (tests/test_specular_taps.cpp).\n");
    std::snprintf(line, sizeof line, "inline constexpr float kSpecularTapResidual[%zu] = {\n", table.size());
    add(line);
    for (std::size_t c = 0; c < table.size(); ++c) {
        std::snprintf(line, sizeof line, "%s%.5ff,%s", c % kGridSize == 0 ? "    " : " ", table[c].residual,
                      c % kGridSize == kGridSize - 1 ? "\n" : "");
        text += line;
    }
    add("};\n#endif\n\nIBL_END_NAMESPACE\n\n#endif\n");
    return text;
}

} // namespace ibl::taps
