// Loading a scene bake through its manifest.json (README "Manifest"): every product the manifest lists,
// with the runtime options its materials asked for. No OpenImageIO/OpenColorIO: KTX2 and JSON only.
#pragma once

#include "iblbake/runtime/runtime.h"

#include <filesystem>
#include <string>

namespace ibl {

struct ManifestProbeSet {
    ProbeSet set;
    // From the manifest's materials: specular off when nothing is glossy (then the set's LD chain and DFG
    // table are 1-texel black placeholders), the diffuse model, energy compensation.
    RuntimeOptions options;
    double calibrationFactor = 1.0; // what the bake multiplied its inputs by
    std::string runtimeProfile;
};

// `path`: manifest.json or the bake directory holding it. Product paths resolve against its directory.
// Throws ibl::Error "<manifest>: <key>: <problem>" for a malformed manifest or a product that cannot be read.
ManifestProbeSet loadProbeSetFromManifest(const std::filesystem::path& path);

} // namespace ibl
