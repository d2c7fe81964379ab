// Loading a scene bake through its manifest.json (docs/formats.md "Manifest"): every product the manifest
// lists, with the runtime options its materials asked for. No OpenImageIO/OpenColorIO: KTX2 and JSON only.
#pragma once

#include "iblbake/runtime/runtime.h"
#include "iblbake/runtime/runtime_light_card.h"

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace ibl {

// One of the scene's area lights (products.lights[]): its AreaLight (sphereAreaLight, diskAreaLight or
// rectangleAreaLight of its geometry, colour and lumens) and, when textured, its card (loadLightCard):
// shade it with shadeAreaLightCpu / shadeTexturedLightCpu or their OpenCL forms.
struct ManifestLight {
    std::string name;
    AreaLight light{};
    std::optional<LightCardData> card;
};

struct ManifestProbeSet {
    ProbeSet set;
    // From the manifest's materials: specular off when nothing is glossy (then the set's LD chain and DFG
    // table are 1-texel black placeholders), the diffuse model, energy compensation.
    RuntimeOptions options;
    double calibrationFactor = 1.0; // what the bake multiplied its inputs by
    std::string runtimeProfile;
    std::vector<ManifestLight> lights; // products.lights, in the scene's order
};

// `path`: manifest.json or the bake directory holding it. Product paths resolve against its directory.
// A local probe gets its visibility from its file (loadLdKtx2, key iblbake.visibility); the manifest's
// products.probes[].visibility must name the convention (premultiplied-alpha in A), and a probe without it
// (every manifest before visibility existed) must have none.
// Throws ibl::Error "<manifest>: <key>: <problem>" for a malformed manifest or a product that cannot be read.
ManifestProbeSet loadProbeSetFromManifest(const std::filesystem::path& path);

} // namespace ibl
