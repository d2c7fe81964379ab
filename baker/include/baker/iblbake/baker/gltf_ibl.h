// A bake as glTF 2.0: the image-based light through EXT_lights_image_based (Khronos glTF repository,
// extensions/2.0/Vendor/EXT_lights_image_based) and the extracted sun through KHR_lights_punctual.
//
// Conventions written (docs/engines.md "glTF 2.0 and Babylon.js"). Where the extension's text is unclear or
// disagrees with Babylon.js (9.28, the loader it was written for), the file follows Babylon, checked by
// numbers in headless Chromium (tests/js/babylon_gltf.mjs):
// - Frame: glTF's (right-handed, +Y up) is docs/conventions.md's, so `rotation` is the identity [0, 0, 0, 1].
// - specularImages[m][f]: level m holds the perceptual roughness stock Babylon reads there (the babylon
//   engine profile, cube_profile.h; not the extension's m / (N - 1), which Babylon does not read);
//   faces +X, -X, +Y, -Y, +Z, -Z. Babylon uploads each
//   image with its rows in the opposite order and, in its default left-handed scene, shows cube
//   direction c at glTF direction (-c.x, c.y, c.z); so image f is our face with +X and -X swapped
//   (f = 0 holds our -X, 1 our +X), turned a half turn (column x, row r = our column N-1-x, row N-1-r).
// - Images: 4-channel PNG, RGBD (iblbake/baker/rgbd.h) of (value / intensity)^(1 / 2.2): Babylon's loader
//   leaves gammaSpace true, so its shaders raise the decoded texel to 2.2 before multiplying by `intensity`
//   (the texture's level). `intensity` is chosen so that the brightest exported channel decodes to RGBD's
//   maximum 255 (255^2.2 after the power): intensity x decoded^2.2 = the bake's value (the stored texel
//   over the KTX2's storage scale).
// - irradianceCoefficients: 9 x [r, g, b] in docs/conventions.md order, s_i E_i / intensity^2 (Babylon's
//   loader scales them by intensity and its shader the irradiance by the level again) with E_i = A_l
// L_i, the
//   SH coefficients of the irradiance E(n) = sum E_i Y_i(n) (our basis, no Condon-Shortley phase), and
//   s_i = -1 for i = 1 (y), 4 (xy), 5 (yz), +1 otherwise: Babylon reads them in its basis (Condon-Shortley
//   signs on i = 1, 3, 5, 7) at the normal in its left-handed frame (x -> -x flips i = 3, 4, 7). From our
//   pre-scaled `sh.irradiance` c_i = A_l k_i L_i: E_i = c_i / k_i.
// - The sun: a KHR_lights_punctual directional light on a node whose rotation turns -Z (the light's
//   direction of travel) to -direction; color = our colour / its largest component (the schema caps
//   color at 1), intensity = illuminance x that component, so intensity x color is our RGB illuminance.
//   The loader maps it through the same root transform as the environment, so both agree in Babylon.
#pragma once

#include "iblbake/baker/sh.h"
#include "iblbake/baker/sun.h"
#include "iblbake/core/cubemap.h"

#include <array>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace ibl {

struct GltfIblScene {
    // The engine profile the file is written for (cube_profile.h kEngineProfiles): its levels, texel
    // encoding (decodeGamma) and SH scaling (shIntensityPower). `iblbake gltf` writes for stock Babylon.js.
    std::string profile = "babylon";
    // Level m holds the roughness the profile's engine reads there (engineLevelRoughness); face sizes halve
    // from level to level.
    CubeMapChain specular;
    // specular's texels are radiance x storageScale (as its KTX2 stores them, "iblbake.storageScale"); the
    // light's intensity carries 1 / storageScale, so that intensity x decoded texel is radiance.
    double storageScale = 1.0;
    ShRgb prescaledIrradiance{}; // our sh.irradiance: A_l k_i L_i (irradianceSH(n) = E(n))
    std::optional<DiskLight> sun;
    bool sunInLux = true;                      // false: the sun's illuminance is in relative units
    std::map<std::string, std::string> extras; // provenance, written as the light's "extras"
};

// s_i c_i / k_i: the coefficients as written (before dividing by the intensity).
ShRgb gltfIrradianceCoefficients(const ShRgb& prescaledIrradiance);
// E(n) from the written coefficients (glTF direction n): sum_i s_i coefficient_i Y_i(n), our irradiance.
glm::dvec3 evalGltfIrradiance(const ShRgb& coefficients, const glm::dvec3& n);
// The light's intensity: the brightest channel of every exported level / 255^decodeGamma (the largest value
// the engine decodes; 1 when the chain is black), over the chain's storage scale.
double gltfIblIntensity(const CubeMapChain& specular, double storageScale = 1.0, double decodeGamma = 1.0);
// The same for a scene, with its profile's decodeGamma.
double gltfIblIntensity(const GltfIblScene& scene);
// glTF quaternion [x, y, z, w] of a node whose -Z axis points along -towardLight.
std::array<double, 4> directionalLightRotation(const glm::dvec3& towardLight);

// Writes `path` (.gltf JSON) and its images beside it, named <stem>_specular_<level>_<face>.png. Every
// file goes to a temporary name first; images are renamed into place, then the glTF. Throws ibl::Error
// "<file>: <problem>".
void writeGltfIbl(const std::filesystem::path& path, const GltfIblScene& scene);

} // namespace ibl
