// Reading the files of a bake directory (what the README's first command writes) for the export commands.
#pragma once

#include <iblbake/baker/products.h>
#include <iblbake/baker/sh.h>

#include <filesystem>
#include <string>

namespace ibl::cli {

// diffuse.json's sh.irradiance (A_l k_i L_i): 9 finite RGB triples; throws ibl::Error naming the file and
// the key path.
ShRgb readPrescaledIrradiance(const std::filesystem::path& diffuseJson);

} // namespace ibl::cli
