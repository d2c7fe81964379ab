// L2 SH of a source cube, clamped-cosine convolution, Filament pre-scaling and deringing windows
// (iblbake/baker/sh.h). The basis itself is kernels/sh.h; the fp64 polynomials below are the same p_i.
#include "iblbake/baker/sh.h"
#include "iblbake/core/error.h"
#include "iblbake/core/numeric.h"

#include <cube.h>
#include <sh.h>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace ibl {
namespace {

constexpr int kGridSize = 64;               // directions per face edge of the non-negativity check
constexpr double kNonNegativeMargin = 1e-6; // times the channel's mean E

using Scalar9 = std::array<double, 9>;

// p_i(n) of kernels/sh.h in fp64, and their gradients in R^3.
Scalar9 polynomials(const glm::dvec3& d) {
    return {
        1.0, d.y, d.z, d.x, d.x * d.y, d.y * d.z, 3.0 * d.z * d.z - 1.0, d.x * d.z, d.x * d.x - d.y * d.y};
}

glm::dvec3 gradient(const Scalar9& c, const glm::dvec3& d) {
    return c[1] * glm::dvec3(0, 1, 0) + c[2] * glm::dvec3(0, 0, 1) + c[3] * glm::dvec3(1, 0, 0) +
           c[4] * glm::dvec3(d.y, d.x, 0) + c[5] * glm::dvec3(0, d.z, d.y) +
           c[6] * glm::dvec3(0, 0, 6.0 * d.z) + c[7] * glm::dvec3(d.z, 0, d.x) +
           c[8] * glm::dvec3(2.0 * d.x, -2.0 * d.y, 0);
}

double value(const Scalar9& c, const glm::dvec3& d) {
    Scalar9 p = polynomials(d);
    double sum = 0.0;
    for (int i = 0; i < 9; ++i)
        sum += c[i] * p[i];
    return sum;
}

Scalar9 channel(const ShRgb& sh, int ch) {
    Scalar9 c;
    for (int i = 0; i < 9; ++i)
        c[i] = sh[i][ch];
    return c;
}

// Descent along the tangential gradient with an adaptive angular step, from `start` (unit).
std::pair<double, glm::dvec3> refineMinimum(const Scalar9& c, glm::dvec3 n) {
    double f = value(c, n);
    double angle = 2.0 / kGridSize;
    for (int iteration = 0; iteration < 400 && angle > 1e-10; ++iteration) {
        glm::dvec3 g = gradient(c, n);
        glm::dvec3 tangential = g - glm::dot(g, n) * n;
        double length = glm::length(tangential);
        if (!(length > 0.0)) break;
        glm::dvec3 candidate = glm::normalize(std::cos(angle) * n - std::sin(angle) * tangential / length);
        double fc = value(c, candidate);
        if (fc < f) {
            n = candidate;
            f = fc;
            angle *= 1.5;
        } else {
            angle *= 0.5;
        }
    }
    return {f, n};
}

constexpr std::size_t kCheckDirections = 6 * std::size_t(kGridSize) * kGridSize;

// Check direction j: the centre of texel j of a kGridSize cube, face after face, row after row. Computed
// where it is needed rather than kept in a table: the table (2.4 MB with its polynomials) was memory
// first touched in every process, a page fault per 4 KB (ingest/read_image.cpp); computing them left the SH
// stage's time as it was (6.4-6.9 ms before, 6.5-6.9 ms after, `iblbake diffuse --timing` of the sample).
glm::dvec3 checkDirection(std::size_t j) {
    const int face = int(j / (std::size_t(kGridSize) * kGridSize));
    const int y = int(j / kGridSize % kGridSize), x = int(j % kGridSize);
    return glm::normalize(
        glm::dvec3(cubeFaceDirection(face, (x + 0.5f) / float(kGridSize), (y + 0.5f) / float(kGridSize))));
}

// E at the check directions for band factors w, channel by channel: mean + w1 band1_j + w2 band2_j, each
// channel's band parts in their own arrays, face after face, so that the scans over the directions
// vectorize.
class NonNegativityCheck {
  public:
    explicit NonNegativityCheck(const ShRgb& radiance) : prescaled_(prescaleIrradiance(radiance)) {
        for (int ch = 0; ch < 3; ++ch) {
            band1_[ch].resize(kCheckDirections);
            band2_[ch].resize(kCheckDirections);
        }
        for (std::size_t j = 0; j < kCheckDirections; ++j) {
            const Scalar9 p = polynomials(checkDirection(j));
            glm::dvec3 b1(0.0), b2(0.0);
            for (int i = 1; i < 4; ++i)
                b1 += prescaled_[i] * p[i];
            for (int i = 4; i < 9; ++i)
                b2 += prescaled_[i] * p[i];
            for (int ch = 0; ch < 3; ++ch) {
                band1_[ch][j] = b1[ch];
                band2_[ch][j] = b2[ch];
            }
        }
        mean_ = prescaled_[0];
    }

    const glm::dvec3& mean() const { return mean_; }

    ShMinimum minimum(const std::array<double, 3>& w) const {
        ShMinimum result;
        for (int ch = 0; ch < 3; ++ch) {
            auto [value, direction] = channelMinimum(ch, w, faceLowest(ch, w));
            result.value[ch] = value;
            result.direction[std::size_t(ch)] = direction;
        }
        return result;
    }

    bool nonNegative(const std::array<double, 3>& w) const {
        // Refinement only lowers the grid's minimum: a channel whose grid is negative decides alone.
        std::array<FaceLowest, 3> lowest;
        for (int ch = 0; ch < 3; ++ch) {
            lowest[std::size_t(ch)] = faceLowest(ch, w);
            const double grid =
                *std::min_element(lowest[std::size_t(ch)].begin(), lowest[std::size_t(ch)].end());
            if (grid < kNonNegativeMargin * mean_[ch]) return false;
        }
        for (int ch = 0; ch < 3; ++ch)
            if (channelMinimum(ch, w, lowest[std::size_t(ch)]).first < kNonNegativeMargin * mean_[ch])
                return false;
        return true;
    }

  private:
    using FaceLowest = std::array<double, 6>;
    static constexpr std::size_t kPerFace = std::size_t(kGridSize) * kGridSize;

    double gridValue(int ch, const std::array<double, 3>& w, std::size_t j) const {
        return mean_[ch] + w[1] * band1_[ch][j] + w[2] * band2_[ch][j];
    }

    // The lowest E of each face's check directions.
    FaceLowest faceLowest(int ch, const std::array<double, 3>& w) const {
        FaceLowest lowest;
        const double mean = mean_[ch], w1 = w[1], w2 = w[2];
        const double* b1 = band1_[ch].data();
        const double* b2 = band2_[ch].data();
        // 8 interleaved running minima (kPerFace is a multiple of 8): independent chains that the
        // compiler vectorizes, where one would wait on each comparison.
        for (std::size_t f = 0; f < 6; ++f) {
            std::array<double, 8> low;
            low.fill(std::numeric_limits<double>::infinity());
            for (std::size_t j = f * kPerFace; j < (f + 1) * kPerFace; j += 8)
                for (std::size_t k = 0; k < 8; ++k)
                    low[k] = std::min(low[k], mean + w1 * b1[j + k] + w2 * b2[j + k]);
            lowest[f] = *std::min_element(low.begin(), low.end());
        }
        return lowest;
    }

    // The minimum of E over the sphere for one channel and its direction, from the faces' lowest grid
    // values. The descent starts from the first direction of a face holding its lowest value, for each
    // face whose lowest value is within a margin of the lowest of all. Between check directions (at most
    // ~0.045 rad apart) E can dip below its samples by at most curvature x 0.0225^2 / 2; for
    // non-negative radiance the curvature is below 6 x the mean E (a delta's L2 irradiance is the worst
    // case), so the dip is under 1.5e-3 of the mean, and a face whose lowest sample is 1e-2 of the mean
    // above the lowest of all cannot hold the minimum. (Windows only lower the curvature.)
    std::pair<double, glm::dvec3> channelMinimum(int ch, const std::array<double, 3>& w,
                                                 const FaceLowest& lowest) const {
        Scalar9 c = channel(prescaled_, ch);
        for (int i = 1; i < 9; ++i)
            c[i] *= w[std::size_t(shBand(i))];
        const double lowestOfAll = *std::min_element(lowest.begin(), lowest.end());
        double best = std::numeric_limits<double>::infinity();
        glm::dvec3 bestDirection(0, 1, 0);
        for (std::size_t f = 0; f < 6; ++f) {
            if (lowest[f] > lowestOfAll + 1e-2 * std::abs(mean_[ch])) continue;
            // The face's first lowest direction, by its own scan: an equality test against lowest[f]
            // would depend on both scans rounding alike.
            std::size_t arg = f * kPerFace;
            double argValue = gridValue(ch, w, arg);
            for (std::size_t j = arg + 1; j < (f + 1) * kPerFace; ++j)
                if (const double e = gridValue(ch, w, j); e < argValue) {
                    arg = j;
                    argValue = e;
                }
            auto [refined, direction] = refineMinimum(c, checkDirection(arg));
            if (refined < best) {
                best = refined;
                bestDirection = direction;
            }
        }
        return {best, bestDirection};
    }

    ShRgb prescaled_;
    std::array<std::vector<double>, 3> band1_, band2_;
    glm::dvec3 mean_{0.0};
};

// Weakest parameter of a family with E >= 0 everywhere, for an E that is negative somewhere without a
// window (callers check that first).
double weakestParameter(const NonNegativityCheck& check, ShWindow family) {
    auto ok = [&](double p) { return check.nonNegative(shWindowFactors(family, p)); };
    if (family == ShWindow::Sloan) { // stronger as lambda grows; find the smallest feasible lambda
        double lo = 0.0, hi = 1e-3;
        while (!ok(hi)) {
            lo = hi;
            hi *= 2.0;
            if (hi > 1e15) throw Error("SH window: no Sloan lambda makes the irradiance non-negative");
        }
        for (int i = 0; i < 60 && hi - lo > 1e-7 * hi; ++i) {
            double mid = 0.5 * (lo + hi);
            (ok(mid) ? hi : lo) = mid;
        }
        return hi;
    }
    // Hanning, Lanczos: weaker as w grows; w <= 1 keeps only band 0, which is the mean and non-negative.
    double lo = 1.0, hi = 2.0;
    while (ok(hi)) {
        lo = hi;
        hi *= 2.0;
        if (hi > 1e12) return lo; // feasible at every practical width
    }
    for (int i = 0; i < 60 && hi - lo > 1e-7 * hi; ++i) {
        double mid = 0.5 * (lo + hi);
        (ok(mid) ? lo : hi) = mid;
    }
    return lo;
}

// Squared L2 change of E over the sphere caused by band factors (Parseval; E_i = A_l L_i).
double windowChange(const ShRgb& radiance, const std::array<double, 3>& w) {
    ShRgb e = convolveClampedCosine(radiance);
    double sum = 0.0;
    for (int i = 1; i < 9; ++i) {
        double k = 1.0 - w[std::size_t(shBand(i))];
        sum += k * k * glm::dot(e[i], e[i]);
    }
    return sum;
}

} // namespace

double texelSolidAngle(int x, int y, int n) {
    const double inv = 2.0 / n;
    const double x0 = x * inv - 1.0, x1 = x0 + inv, y0 = y * inv - 1.0, y1 = y0 + inv;
    return cubeRectangleSolidAngleF64(x0, y0, x1, y1);
}

namespace {
// sum_x r[x] w[x] in 8 interleaved partial sums: independent chains that the compiler vectorizes, where
// one running sum would wait on each addition.
double dotProduct(const double* r, const double* w, std::size_t count) {
    std::array<double, 8> partial{};
    std::size_t x = 0;
    for (; x + 8 <= count; x += 8)
        for (std::size_t k = 0; k < 8; ++k)
            partial[k] += r[x + k] * w[x + k];
    for (; x < count; ++x)
        partial[0] += r[x] * w[x];
    return ((partial[0] + partial[1]) + (partial[2] + partial[3])) +
           ((partial[4] + partial[5]) + (partial[6] + partial[7]));
}
} // namespace

ShRgb projectRadianceSH(const CubeMap& source) {
    const int n = source.faceSize;
    if (n <= 0) throw Error("SH projection: empty source cube");
    const std::size_t width = std::size_t(n);
    const double inv = 2.0 / n;
    // Rows of texels in tasks over all six faces: the faces share their texels' solid angles. Per face
    // row, the texels' weights Y_i(d) omega and radiances go to arrays first, then each of the 27 sums
    // is a dot product over the row.
    std::vector<std::array<double, 27>> rows(width);
    tbb::parallel_for(tbb::blocked_range<int>(0, n), [&](const tbb::blocked_range<int>& range) {
        std::vector<double> omega(width), weights(9 * width), radiance(3 * width);
        std::vector<float> s(width); // the texels' face coordinate along the row
        for (std::size_t x = 0; x < width; ++x)
            s[x] = (float(x) + 0.5f) / float(n);
        // The area elements of the texel corners above and below the row, each row of corners computed
        // once per task: texelSolidAngle() = top - bottom - next top + next bottom.
        std::vector<double> top(width + 1), bottom(width + 1);
        auto cornerRow = [&](std::vector<double>& corners, double v) {
            for (std::size_t x = 0; x <= width; ++x)
                corners[x] = cubeAreaElementF64(double(x) * inv - 1.0, v);
        };
        double y0 = range.begin() * inv - 1.0;
        cornerRow(top, y0);
        for (int y = range.begin(); y < range.end(); ++y) {
            const double y1 = y0 + inv;
            cornerRow(bottom, y1);
            for (std::size_t x = 0; x < width; ++x)
                omega[x] = top[x] - bottom[x] - top[x + 1] + bottom[x + 1];
            std::swap(top, bottom);
            y0 = y1;
            const float t = (float(y) + 0.5f) / float(n);
            std::array<double, 27> sum{};
            for (int face = 0; face < 6; ++face) {
                const glm::vec4* texels = &source.faces[std::size_t(face)].at(0, y);
                for (std::size_t x = 0; x < width; ++x) {
                    vec3 d = glm::normalize(cubeFaceDirection(face, s[x], t));
                    ShBasis basis = shBasis(d);
                    for (std::size_t i = 0; i < 9; ++i)
                        weights[i * width + x] = double(basis.v[i]) * omega[x];
                    for (std::size_t c = 0; c < 3; ++c)
                        radiance[c * width + x] = texels[x][int(c)];
                }
                for (std::size_t i = 0; i < 9; ++i)
                    for (std::size_t c = 0; c < 3; ++c)
                        sum[3 * i + c] += dotProduct(&radiance[c * width], &weights[i * width], width);
            }
            rows[std::size_t(y)] = sum;
        }
    });
    ShRgb sh{};
    for (const std::array<double, 27>& r : rows) // fixed order: deterministic
        for (int i = 0; i < 9; ++i)
            sh[i] += glm::dvec3(r[3 * i], r[3 * i + 1], r[3 * i + 2]);
    return sh;
}

ShRgb convolveClampedCosine(const ShRgb& radiance) {
    ShRgb e;
    for (int i = 0; i < 9; ++i)
        e[i] = radiance[i] * double(shClampedCosineFactor(shBand(i)));
    return e;
}

ShRgb prescaleIrradiance(const ShRgb& radiance) {
    ShRgb c;
    for (int i = 0; i < 9; ++i)
        c[i] = radiance[i] * (double(shClampedCosineFactor(shBand(i))) * double(shBasisConstant(i)));
    return c;
}

glm::dvec3 evalRadianceSH(const ShRgb& radiance, const glm::dvec3& n) {
    Scalar9 p = polynomials(n);
    glm::dvec3 sum(0.0);
    for (int i = 0; i < 9; ++i)
        sum += radiance[i] * (double(shBasisConstant(i)) * p[i]);
    return sum;
}

glm::dvec3 evalPrescaledSH(const ShRgb& prescaled, const glm::dvec3& n) {
    Scalar9 p = polynomials(n);
    glm::dvec3 sum(0.0);
    for (int i = 0; i < 9; ++i)
        sum += prescaled[i] * p[i];
    return sum;
}

glm::dvec3 evalIrradianceSH(const ShRgb& radiance, const glm::dvec3& n) {
    return evalPrescaledSH(prescaleIrradiance(radiance), n);
}

ShWindow parseShWindow(const std::string& name) {
    if (name == "none") return ShWindow::None;
    if (name == "sloan") return ShWindow::Sloan;
    if (name == "hanning") return ShWindow::Hanning;
    if (name == "lanczos") return ShWindow::Lanczos;
    throw SettingError("window", "'" + name + "' is not one of auto, none, sloan, hanning, lanczos");
}

const char* shWindowName(ShWindow window) {
    switch (window) {
    case ShWindow::Sloan:
        return "sloan";
    case ShWindow::Hanning:
        return "hanning";
    case ShWindow::Lanczos:
        return "lanczos";
    default:
        return "none";
    }
}

std::array<double, 3> shWindowFactors(ShWindow window, double parameter) {
    std::array<double, 3> w{1.0, 1.0, 1.0};
    for (int l = 1; l <= 2; ++l) {
        double x = kPi * l / parameter;
        switch (window) {
        case ShWindow::Sloan:
            w[std::size_t(l)] = 1.0 / (1.0 + parameter * l * l * (l + 1) * (l + 1));
            break;
        case ShWindow::Hanning:
            w[std::size_t(l)] = l < parameter ? 0.5 * (1.0 + std::cos(x)) : 0.0;
            break;
        case ShWindow::Lanczos:
            w[std::size_t(l)] = l < parameter ? std::sin(x) / x : 0.0;
            break;
        default:
            break;
        }
    }
    return w;
}

ShRgb applyShWindow(const ShRgb& coefficients, const std::array<double, 3>& factors) {
    ShRgb out;
    for (int i = 0; i < 9; ++i)
        out[i] = coefficients[i] * factors[std::size_t(shBand(i))];
    return out;
}

ShMinimum minimumIrradiance(const ShRgb& radiance) {
    return NonNegativityCheck(radiance).minimum({1.0, 1.0, 1.0});
}

ShWindowResult chooseShWindow(const ShRgb& radiance, const ShWindowSettings& settings) {
    NonNegativityCheck check(radiance);
    ShWindowResult result;
    result.meanIrradiance = check.mean();
    result.minBefore = check.minimum({1.0, 1.0, 1.0}).value;

    auto finish = [&](ShWindow window, double parameter, bool searched) {
        result.window = window;
        result.parameter = window == ShWindow::None ? 0.0 : parameter;
        result.factors = window == ShWindow::None ? std::array<double, 3>{1.0, 1.0, 1.0}
                                                  : shWindowFactors(window, parameter);
        result.searched = searched;
        result.minAfter = check.minimum(result.factors).value;
        return result;
    };

    if (!settings.automatic) {
        if (settings.window == ShWindow::None) return finish(ShWindow::None, 0.0, false);
        if (settings.parameter) {
            double p = *settings.parameter;
            if (!(p >= 0.0) || (settings.window != ShWindow::Sloan && !(p > 0.0)) || !std::isfinite(p))
                throw SettingError("windowParameter",
                                   std::to_string(p) + " is not valid for the " +
                                       shWindowName(settings.window) +
                                       " window (Sloan: lambda >= 0; Hanning, Lanczos: width w > 0)");
            return finish(settings.window, p, false);
        }
    }
    if (check.nonNegative({1.0, 1.0, 1.0})) return finish(ShWindow::None, 0.0, true); // nothing to fix
    if (!settings.automatic) return finish(settings.window, weakestParameter(check, settings.window), true);

    // The three searches are independent: run them side by side, then compare in a fixed order.
    const std::array<ShWindow, 3> families{ShWindow::Sloan, ShWindow::Hanning, ShWindow::Lanczos};
    std::array<double, 3> parameters{};
    tbb::parallel_for(
        0, 3, [&](int k) { parameters[std::size_t(k)] = weakestParameter(check, families[std::size_t(k)]); });
    ShWindow best = ShWindow::None;
    double bestParameter = 0.0, bestChange = std::numeric_limits<double>::infinity();
    for (std::size_t k = 0; k < families.size(); ++k) {
        double change = windowChange(radiance, shWindowFactors(families[k], parameters[k]));
        if (change < bestChange) {
            best = families[k];
            bestParameter = parameters[k];
            bestChange = change;
        }
    }
    return finish(best, bestParameter, true);
}

DiffuseSH bakeDiffuseSH(const CubeMap& source, const ShWindowSettings& settings) {
    DiffuseSH out;
    out.radianceRaw = projectRadianceSH(source);
    out.window = chooseShWindow(out.radianceRaw, settings);
    out.radiance = applyShWindow(out.radianceRaw, out.window.factors);
    out.irradiance = prescaleIrradiance(out.radiance);
    for (int i = 0; i < 9; ++i)
        out.irradianceOverPi[i] = out.irradiance[i] / kPi;
    return out;
}

} // namespace ibl
