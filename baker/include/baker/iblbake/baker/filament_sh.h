// Diffuse SH in Filament's conventions: the text of cmgen's sh.txt (cmgen --sh-shader, irradiance), which
// Filament's samples read line by line with sscanf("(%f,%f,%f)") and pass to
// IndirectLight::Builder::irradiance(3, sh). cmgen projects in a basis with the Condon-Shortley phase,
// convolves with the clamped cosine and multiplies by the signed basis constants and 1/pi
// (CubemapSH::preprocessSHForShader), so the signs cancel: coefficient i = A_l k_i L_i / pi, to be
// evaluated as sum_i c_i p_i(n) with p = 1, y, z, x, xy, yz, 3z^2 - 1, xz, x^2 - y^2 -- our
// irradianceOverPi. Its result is E(n)/pi; times the diffuse colour it is the Lambert radiance.
#pragma once

#include "iblbake/baker/sh.h"

#include <string>

namespace ibl {

// From our pre-scaled sh.irradiance (A_l k_i L_i): nine lines "(r, g, b); // Llm, irradiance, pre-scaled
// base", as cmgen writes them.
std::string filamentShText(const ShRgb& prescaledIrradiance);

// The same coefficients as the value of the KTX1 key "sh" cmgen writes into <name>_ibl.ktx: nine lines
// "r g b", which Filament's Ktx1Bundle::getSphericalHarmonics and filament.js createIblFromKtx1 read as 27
// numbers separated by white space.
std::string filamentShMetadata(const ShRgb& prescaledIrradiance);

} // namespace ibl
