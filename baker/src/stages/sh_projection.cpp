// L2 SH of a source cube, clamped-cosine convolution, Filament pre-scaling and deringing windows
// (iblbake/baker/sh.h). The basis itself is kernels/sh.h; the fp64 polynomials below are the same p_i.
#include "iblbake/baker/sh.h"
#include "iblbake/core/error.h"

#include <cube.h>
#include <sh.h>

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace ibl {
namespace {

constexpr double kPi = 3.14159265358979323846;
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

// The check directions: texel centres of a kGridSize cube, with their band-1 and band-2 parts of E
// precomputed per radiance, so that a window is checked with 2 multiply-adds per direction and channel.
struct Grid {
    std::vector<glm::dvec3> directions;
    std::vector<Scalar9> p;
    static const Grid& get() {
        static const Grid grid = [] {
            Grid g;
            for (int f = 0; f < 6; ++f)
                for (int y = 0; y < kGridSize; ++y)
                    for (int x = 0; x < kGridSize; ++x) {
                        glm::dvec3 d = glm::normalize(glm::dvec3(cubeFaceDirection(
                            f, (x + 0.5f) / float(kGridSize), (y + 0.5f) / float(kGridSize))));
                        g.directions.push_back(d);
                        g.p.push_back(polynomials(d));
                    }
            return g;
        }();
        return grid;
    }
};

class NonNegativityCheck {
  public:
    explicit NonNegativityCheck(const ShRgb& radiance) : prescaled_(prescaleIrradiance(radiance)) {
        const Grid& grid = Grid::get();
        band1_.resize(grid.p.size());
        band2_.resize(grid.p.size());
        for (std::size_t j = 0; j < grid.p.size(); ++j) {
            glm::dvec3 b1(0.0), b2(0.0);
            for (int i = 1; i < 4; ++i)
                b1 += prescaled_[i] * grid.p[j][i];
            for (int i = 4; i < 9; ++i)
                b2 += prescaled_[i] * grid.p[j][i];
            band1_[j] = b1;
            band2_[j] = b2;
        }
        mean_ = prescaled_[0];
    }

    const glm::dvec3& mean() const { return mean_; }

    // Lowest E over the check directions (no refinement), per channel.
    glm::dvec3 gridMinimum(const std::array<double, 3>& w) const {
        glm::dvec3 lowest(std::numeric_limits<double>::infinity());
        for (std::size_t j = 0; j < band1_.size(); ++j)
            lowest = glm::min(lowest, mean_ + w[1] * band1_[j] + w[2] * band2_[j]);
        return lowest;
    }

    ShMinimum minimum(const std::array<double, 3>& w) const {
        const Grid& grid = Grid::get();
        const std::size_t perFace = std::size_t(kGridSize) * kGridSize;
        ShMinimum result;
        for (int ch = 0; ch < 3; ++ch) {
            Scalar9 c = channel(prescaled_, ch);
            for (int i = 1; i < 9; ++i)
                c[i] *= w[std::size_t(shBand(i))];
            // Each face's lowest check direction; the descent starts from those within a margin of the
            // lowest of all. Between check directions (at most ~0.045 rad apart) E can dip below its
            // samples by at most curvature x 0.0225^2 / 2; for non-negative radiance the curvature is
            // below 6 x the mean E (a delta's L2 irradiance is the worst case), so the dip is under
            // 1.5e-3 of the mean, and a face whose lowest sample is 1e-2 of the mean above the lowest of
            // all cannot hold the minimum. (Windows only lower the curvature.)
            std::array<std::size_t, 6> arg{};
            std::array<double, 6> lowest;
            lowest.fill(std::numeric_limits<double>::infinity());
            for (int f = 0; f < 6; ++f)
                for (std::size_t j = f * perFace; j < (f + 1) * perFace; ++j) {
                    double e = mean_[ch] + w[1] * band1_[j][ch] + w[2] * band2_[j][ch];
                    if (e < lowest[std::size_t(f)]) {
                        lowest[std::size_t(f)] = e;
                        arg[std::size_t(f)] = j;
                    }
                }
            const double lowestOfAll = *std::min_element(lowest.begin(), lowest.end());
            double best = std::numeric_limits<double>::infinity();
            glm::dvec3 bestDirection(0, 1, 0);
            for (std::size_t f = 0; f < 6; ++f) {
                if (lowest[f] > lowestOfAll + 1e-2 * std::abs(mean_[ch])) continue;
                auto [refined, direction] = refineMinimum(c, grid.directions[arg[f]]);
                if (refined < best) {
                    best = refined;
                    bestDirection = direction;
                }
            }
            result.value[ch] = best;
            result.direction[std::size_t(ch)] = bestDirection;
        }
        return result;
    }

    bool nonNegative(const std::array<double, 3>& w) const {
        glm::dvec3 grid = gridMinimum(w); // refinement only lowers it: a negative grid point decides
        for (int ch = 0; ch < 3; ++ch)
            if (grid[ch] < kNonNegativeMargin * mean_[ch]) return false;
        ShMinimum m = minimum(w);
        for (int ch = 0; ch < 3; ++ch)
            if (m.value[ch] < kNonNegativeMargin * mean_[ch]) return false;
        return true;
    }

  private:
    ShRgb prescaled_;
    std::vector<glm::dvec3> band1_, band2_;
    glm::dvec3 mean_{0.0};
};

// Weakest parameter of a family with E >= 0 everywhere; nullopt when no window is needed.
std::optional<double> weakestParameter(const NonNegativityCheck& check, ShWindow family) {
    if (check.nonNegative({1.0, 1.0, 1.0})) return std::nullopt;
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

namespace {
double areaElement(double u, double v) {
    return std::atan2(u * v, std::sqrt(u * u + v * v + 1.0));
}
} // namespace

double texelSolidAngle(int x, int y, int n) {
    const double inv = 2.0 / n;
    const double x0 = x * inv - 1.0, x1 = x0 + inv, y0 = y * inv - 1.0, y1 = y0 + inv;
    return areaElement(x0, y0) - areaElement(x0, y1) - areaElement(x1, y0) + areaElement(x1, y1);
}

ShRgb projectRadianceSH(const CubeMap& source) {
    const int n = source.faceSize;
    if (n <= 0) throw Error("SH projection: empty source cube");
    // One task per row index y, over all six faces: the faces share their texels' solid angles.
    std::vector<std::array<double, 27>> rows(static_cast<std::size_t>(n));
    tbb::parallel_for(0, n, [&](int y) {
        // texelSolidAngle() of the row, each corner's area element computed once.
        std::vector<double> omega(static_cast<std::size_t>(n));
        const double inv = 2.0 / n, y0 = y * inv - 1.0, y1 = y0 + inv;
        double top = areaElement(-1.0, y0), bottom = areaElement(-1.0, y1);
        for (int x = 0; x < n; ++x) {
            const double x1 = (x + 1) * inv - 1.0;
            const double nextTop = areaElement(x1, y0), nextBottom = areaElement(x1, y1);
            omega[std::size_t(x)] = top - bottom - nextTop + nextBottom;
            top = nextTop;
            bottom = nextBottom;
        }
        std::array<double, 27> sum{};
        for (int face = 0; face < 6; ++face)
            for (int x = 0; x < n; ++x) {
                vec3 d = glm::normalize(
                    cubeFaceDirection(face, (float(x) + 0.5f) / float(n), (float(y) + 0.5f) / float(n)));
                ShBasis basis = shBasis(d);
                const glm::vec4& p = source.faces[std::size_t(face)].at(x, y);
                for (int i = 0; i < 9; ++i) {
                    const double w = double(basis.v[i]) * omega[std::size_t(x)];
                    sum[3 * i] += p.x * w;
                    sum[3 * i + 1] += p.y * w;
                    sum[3 * i + 2] += p.z * w;
                }
            }
        rows[std::size_t(y)] = sum;
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
        std::optional<double> p = weakestParameter(check, settings.window);
        return p ? finish(settings.window, *p, true) : finish(ShWindow::None, 0.0, true);
    }

    ShWindow best = ShWindow::None;
    double bestParameter = 0.0, bestChange = std::numeric_limits<double>::infinity();
    for (ShWindow family : {ShWindow::Sloan, ShWindow::Hanning, ShWindow::Lanczos}) {
        std::optional<double> p = weakestParameter(check, family);
        if (!p) return finish(ShWindow::None, 0.0, true); // nothing to fix
        double change = windowChange(radiance, shWindowFactors(family, *p));
        if (change < bestChange) {
            best = family;
            bestParameter = *p;
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
