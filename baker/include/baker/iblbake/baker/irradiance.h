// The diffuse irradiance cube. Every texel stores E(n) / pi = (1 / pi) integral L(l) max(0, n.l) dl,
// the cosine-weighted mean radiance over the hemisphere around its direction n: the LD term of a Lambert
// lobe that Frostbite's Listing 20 returns and its runtime multiplies by the DFG LUT's diffuse term and
// the albedo (a constant environment L stores L; irradiance is pi times the stored value). Filament's
// pre-scaled SH with the 1/pi folded in (DiffuseSH::irradianceOverPi) evaluate to the same quantity.
#pragma once

#include "iblbake/baker/sh.h"
#include "iblbake/baker/specular.h" // Quality
#include "iblbake/core/cubemap.h"
#include "iblbake/opencl/executor.h"

#include <cstdint>
#include <string>

namespace ibl {

enum class IrradianceMethod {
    Sampled, // cosine importance sampling with pre-filtered lookups + exact bright texels (irradiance.h)
    SH,      // the L2 irradiance SH evaluated at each texel (cheaper, band-limited)
};
IrradianceMethod parseIrradianceMethod(const std::string& name); // "sampled" | "sh"; throws ibl::Error
const char* irradianceMethodName(IrradianceMethod method);

struct IrradianceSettings {
    int faceSize = 32; // output face size
    // Cosine samples per texel; 0: from the quality preset: draft 128, production 512, reference 4096
    // (worst relative mean error against the brute force over the shared HDRIs at 256-px source faces:
    // 1.9%, 0.55%, < 0.1%).
    std::uint32_t samples = 0;
    Quality quality = Quality::Production;
    // Texels brighter than brightThreshold x the solid-angle-weighted mean luminance (at most
    // maxBrightTexels of them, the brightest) are integrated exactly instead of by sampling. The exact
    // term costs one multiply-add per texel and entry, so the list can be much longer than the LD one.
    float brightThreshold = 16.0f;
    std::uint32_t maxBrightTexels = 4096;
    // Added to 0.5 log2(omegaS / omegaP) of every sample before rounding to a whole level. -0.5 (i.e.
    // rounding down) measured best of -1, -0.5, 0, 0.5, 1 on the shared HDRIs at 64 to 2048 samples
    // (256-px source faces, against referenceIrradianceCube); 0 is up to 1.5x and +1 up to 3x worse.
    float lodBias = -0.5f;
};

std::uint32_t irradianceSamplesFor(const IrradianceSettings& settings);

// Sampled method (OpenCL kernel kernels/irradiance.cl or the TBB path, same functions). The source face
// size must be a power of two (it gets a mip pyramid). Stores E / pi.
CubeMap bakeIrradianceCube(const CubeMap& source, const IrradianceSettings& settings,
                           const Executor& executor);

// SH method: irradianceSH(n) / pi of pre-scaled irradiance coefficients (DiffuseSH::irradiance) at each
// texel centre, negative values (ringing) clamped to 0 and counted in *clampedTexels. Stores E / pi.
CubeMap irradianceCubeFromSH(const ShRgb& prescaledIrradiance, int faceSize,
                             std::uint64_t* clampedTexels = nullptr);

// Brute-force reference: every source texel, L max(0, n.l) omega summed in fp64 at each output texel
// centre, divided by pi (so it compares with the cubes above). Tests and accuracy reports only.
CubeMap referenceIrradianceCube(const CubeMap& source, int faceSize);

} // namespace ibl
