// What storing a cube chain in a format costs (docs/formats.md "Format cost"): the file's and the GPU's
// bytes, the encode time, and the error of the stored texels against the float chain, level by level.
#pragma once

#include "iblbake/core/cubemap.h"
#include "iblbake/ktx2/ktx2.h"

#include <nlohmann/json.hpp>

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace ibl {

// One level's error: per texel sum |stored - float| / sum float over RGB (the absolute difference where the
// float texel is black), its mean and 99th percentile over the level's texels.
struct LevelStorageError {
    int faceSize = 0;
    double meanRelative = 0.0;
    double p99Relative = 0.0;
};

struct FormatCost {
    std::string format;          // a kKtx2FormatNames name
    std::uint64_t fileBytes = 0; // the KTX2 file
    std::uint64_t gpuBytes = 0;  // every level's images as the GPU holds them
    double encodeSeconds = 0.0;  // the writer's texel encoding (BC6H: the block encoder), this machine
    double storageScale = 1.0;   // iblbake.storageScale chosen for the format
    std::vector<LevelStorageError> levels; // the levels of faces of at least 4 px
};

// The errors of `stored` (the texels read back, divided by the storage scale) against `reference`, for the
// levels of faces of at least 4 px.
std::vector<LevelStorageError> storageErrors(const CubeMapChain& reference,
                                             const std::vector<std::vector<ImageRGBA>>& stored);

// Writes `chain` in `format` (with the storage scale a product would get) to a file in `scratch`, reads it
// back through readKtx2 and measures it; the file is removed.
FormatCost measureFormatCost(const CubeMapChain& chain, Ktx2Format format,
                             const std::filesystem::path& scratch);

// `iblbake format-cost CHAIN`: the chain file (best rgba32f: the reference the errors are measured against)
// read back to radiance and measured in each of `formats` (kKtx2FormatNames names), in a scratch directory
// under the system's temporary directory that is removed afterwards. Throws ibl::Error naming the file when
// it is not a cube map chain.
std::vector<FormatCost> measureChainFormatCosts(const std::filesystem::path& chainFile,
                                                const std::vector<std::string>& formats);

// One line per format and level for the commands: "bc6h  526,064 B file  524,288 B GPU  312.4 ms  level 0
// 256 px mean 0.412% p99 1.73%" (the time only with `withTime`, so that a test can compare two runs).
std::string formatCostText(const std::vector<FormatCost>& costs, bool withTime);
nlohmann::json formatCostToJson(const FormatCost& cost, bool withTime);
// `iblbake format-cost --json`: {chain, formats: [formatCostToJson with the time]}.
nlohmann::json formatCostsJson(const std::string& chain, const std::vector<FormatCost>& costs);

} // namespace ibl
