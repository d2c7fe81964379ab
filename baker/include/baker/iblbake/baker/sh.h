// Diffuse lighting as L2 spherical harmonics (docs/conventions.md "SH"; kernels/sh.h has the basis):
// projection of a source cube, clamped-cosine convolution, Filament's pre-scaling, and deringing windows.
//
// Conventions of the coefficient sets (9 RGB coefficients each, docs/conventions.md order):
//   radiance          L_i = integral L(w) Y_i(w) dw                                (standard normalization)
//   irradiance        A_l k_i L_i: Filament's irradianceSH(n) = sum_i c_i p_i(n) returns the irradiance
//                     E(n) = integral L(w) max(0, n.w) dw, in the input's units times sr
//   irradianceOverPi  the same divided by pi (the Lambert 1/pi folded in, as Filament's cmgen does):
//                     irradianceSH(n) returns E(n) / pi, the cosine-weighted mean radiance, which is also
//                     what the irradiance cube stores (kernels/irradiance.h, Frostbite Listing 20)
// A deringing window multiplies band l of every set by w_l (w_0 = 1), which keeps the mean E.
#pragma once

#include "iblbake/core/cubemap.h"

#include <array>
#include <optional>
#include <string>

#include <glm/vec3.hpp>

namespace ibl {

// 9 RGB coefficients in docs/conventions.md order, fp64.
using ShRgb = std::array<glm::dvec3, 9>;

// Exact solid angle of texel (x, y) of an n-texel cube face, evaluated in fp64 (kernels/cube.h's
// cubeTexelSolidAngle formula; in fp32 the difference of four O(1) terms loses ~1e-3 at 256 texels).
double texelSolidAngle(int x, int y, int n);

// L_i = sum over every texel of L(texel) Y_i(centre direction) exact solid angle; fp64 sums, split over
// rows with TBB and added in a fixed order (the result does not depend on the thread count).
ShRgb projectRadianceSH(const CubeMap& source);

// A_l L_i: the irradiance's own SH coefficients (not pre-scaled).
ShRgb convolveClampedCosine(const ShRgb& radiance);
// A_l k_i L_i: Filament's irradianceSH(n) returns E(n) from these.
ShRgb prescaleIrradiance(const ShRgb& radiance);

// fp64 evaluations (n unit): sum L_i Y_i(n); E(n) from radiance coefficients; irradianceSH(n).
glm::dvec3 evalRadianceSH(const ShRgb& radiance, const glm::dvec3& n);
glm::dvec3 evalIrradianceSH(const ShRgb& radiance, const glm::dvec3& n);
glm::dvec3 evalPrescaledSH(const ShRgb& prescaled, const glm::dvec3& n);

// Deringing windows, band factors w_l (w_0 = 1):
//   Sloan   1 / (1 + lambda l^2 (l + 1)^2), lambda >= 0 (Sloan 2008, "Stupid Spherical Harmonics (SH)
//           Tricks": the minimizer of squared error plus lambda times the squared Laplacian). Larger
//           lambda = stronger; 0 = no window.
//   Hanning (1 + cos(pi l / w)) / 2 for l < w, else 0; w > 0 in bands. Larger w = weaker.
//   Lanczos sin(pi l / w) / (pi l / w) for l < w, else 0; w > 0 in bands. Larger w = weaker.
enum class ShWindow { None, Sloan, Hanning, Lanczos };
ShWindow parseShWindow(const std::string& name); // none, sloan, hanning, lanczos; throws ibl::Error
const char* shWindowName(ShWindow window);
std::array<double, 3> shWindowFactors(ShWindow window, double parameter);
ShRgb applyShWindow(const ShRgb& coefficients, const std::array<double, 3>& factors);

// Minimum of E(n) reconstructed from radiance coefficients over the whole sphere, per channel: the
// lowest of a 64 x 64-per-face cube of directions, refined by projected gradient descent from each face's
// lowest direction (E is a quadratic polynomial on the sphere, so this finds the true minimum).
struct ShMinimum {
    glm::dvec3 value{0.0};
    std::array<glm::dvec3, 3> direction{}; // where each channel's minimum lies
};
ShMinimum minimumIrradiance(const ShRgb& radiance);

struct ShWindowSettings {
    // automatic: no window when E >= 0 everywhere, else of the three families' weakest windows with
    // E >= 0 everywhere, the one that changes E least (L2 over the sphere).
    bool automatic = true;
    ShWindow window = ShWindow::None;
    // For a family without a parameter: its weakest parameter with E >= 0 everywhere (None when the
    // unwindowed E already is).
    std::optional<double> parameter;
};

struct ShWindowResult {
    ShWindow window = ShWindow::None;
    double parameter = 0.0; // lambda (Sloan) or w (Hanning, Lanczos); 0 for None
    std::array<double, 3> factors{1.0, 1.0, 1.0};
    bool searched = false;          // parameter found by the non-negativity search
    glm::dvec3 minBefore{0.0};      // minimum of E over the sphere without the window, per channel
    glm::dvec3 minAfter{0.0};       // ... with it
    glm::dvec3 meanIrradiance{0.0}; // mean of E over the sphere (A_0 k_0 L_0), unchanged by windows
};

// Non-negativity means E >= 1e-6 x the channel's mean E at the true minimum (a margin for fp32
// evaluation at run time). Throws ibl::Error for a negative window parameter.
ShWindowResult chooseShWindow(const ShRgb& radiance, const ShWindowSettings& settings);

struct DiffuseSH {
    ShRgb radianceRaw;      // the projection, unwindowed
    ShRgb radiance;         // windowed
    ShRgb irradiance;       // windowed, pre-scaled: irradianceSH(n) = E(n)
    ShRgb irradianceOverPi; // irradiance / pi: irradianceSH(n) = E(n) / pi
    ShWindowResult window;
};

DiffuseSH bakeDiffuseSH(const CubeMap& source, const ShWindowSettings& settings);

// The SH window's report (`iblbake diffuse`): the window chosen, and the smallest irradiance before and
// after it, per channel and as the worst channel's percentage of its mean; two lines, of SH projected from
// `faceSize` px faces.
std::string shWindowText(const ShWindowResult& window, int faceSize);

} // namespace ibl
