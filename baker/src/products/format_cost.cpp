// The cost of a format (iblbake/baker/format_cost.h).
#include "iblbake/baker/format_cost.h"

#include "iblbake/baker/products.h"
#include "iblbake/core/error.h"
#include "iblbake/core/temporary_path.h"
#include "iblbake/ktx2/ktx2.h"
#include "iblbake/ktx2/storage_scale.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace ibl {

namespace fs = std::filesystem;

std::vector<LevelStorageError> storageErrors(const CubeMapChain& reference,
                                             const std::vector<std::vector<ImageRGBA>>& stored) {
    std::vector<LevelStorageError> levels;
    for (std::size_t m = 0; m < reference.levels.size() && m < stored.size(); ++m) {
        const CubeMap& level = reference.levels[m];
        if (level.faceSize < 4) break;
        std::vector<double> errors;
        for (std::size_t f = 0; f < level.faces.size(); ++f)
            for (std::size_t i = 0; i < level.faces[f].pixels.size(); ++i) {
                const glm::vec4& r = level.faces[f].pixels[i];
                const glm::vec4& s = stored[m][f].pixels[i];
                double difference = 0.0, sum = 0.0;
                for (int c = 0; c < 3; ++c) {
                    difference += std::fabs(double(s[c]) - double(r[c]));
                    sum += std::fabs(double(r[c]));
                }
                errors.push_back(sum > 0.0 ? difference / sum : difference);
            }
        LevelStorageError e;
        e.faceSize = level.faceSize;
        for (double v : errors)
            e.meanRelative += v / double(errors.size());
        const std::size_t rank =
            std::min(errors.size() - 1, std::size_t(std::ceil(0.99 * double(errors.size()))) - 1);
        std::nth_element(errors.begin(), errors.begin() + std::ptrdiff_t(rank), errors.end());
        e.p99Relative = errors[rank];
        levels.push_back(e);
    }
    return levels;
}

FormatCost measureFormatCost(const CubeMapChain& chain, Ktx2Format format, const fs::path& scratch) {
    FormatCost cost;
    cost.format = kKtx2FormatNames.at(std::size_t(format));
    const fs::path file = scratch / (cost.format + ".ktx2");
    const ProductStorage storage = chooseProductStorage(chain, format, false);
    const Ktx2WriteStats stats = writeProductCube(file, chain, format, {}, storage);
    cost.fileBytes = stats.fileBytes;
    cost.gpuBytes = stats.gpuBytes;
    cost.encodeSeconds = stats.encodeSeconds;
    cost.storageScale = storage.scale;
    Ktx2Image stored = readKtx2(file);
    unscaleKtx2Texels(stored);
    std::error_code ignored;
    fs::remove(file, ignored);
    cost.levels = storageErrors(chain, stored.levels);
    return cost;
}

std::vector<FormatCost> measureChainFormatCosts(const fs::path& chainFile,
                                                const std::vector<std::string>& formats) {
    Ktx2Image image = readKtx2(chainFile);
    if (image.faceCount != 6 || image.layerCount != 0)
        throw Error(chainFile.string() + ": not a cube map chain");
    unscaleKtx2Texels(image);
    CubeMapChain chain;
    for (std::vector<ImageRGBA>& faces : image.levels) {
        CubeMap level;
        level.faceSize = faces.front().width;
        for (std::size_t f = 0; f < 6; ++f)
            level.faces[f] = std::move(faces[f]);
        chain.levels.push_back(std::move(level));
    }
    const fs::path scratch = temporaryPathBeside(fs::temp_directory_path() / "iblbake-format-cost");
    fs::create_directories(scratch);
    std::vector<FormatCost> costs;
    std::error_code ignored;
    try {
        for (const std::string& name : formats)
            costs.push_back(measureFormatCost(chain, parseKtx2Format(name), scratch));
    } catch (...) {
        fs::remove_all(scratch, ignored);
        throw;
    }
    fs::remove_all(scratch, ignored);
    return costs;
}

nlohmann::json formatCostsJson(const std::string& chain, const std::vector<FormatCost>& costs) {
    nlohmann::json out = {{"chain", chain}, {"formats", nlohmann::json::array()}};
    for (const FormatCost& c : costs)
        out["formats"].push_back(formatCostToJson(c, true));
    return out;
}

std::string formatCostText(const std::vector<FormatCost>& costs, bool withTime) {
    std::string text;
    char line[200];
    for (const FormatCost& c : costs) {
        std::snprintf(line, sizeof line, "format  %-10s %12llu B file %12llu B GPU", c.format.c_str(),
                      static_cast<unsigned long long>(c.fileBytes),
                      static_cast<unsigned long long>(c.gpuBytes));
        text += line;
        if (withTime) {
            std::snprintf(line, sizeof line, "  encode %8.1f ms", 1000.0 * c.encodeSeconds);
            text += line;
        }
        if (c.storageScale != 1.0) {
            std::snprintf(line, sizeof line, "  storage scale %g", c.storageScale);
            text += line;
        }
        text += "\n";
        for (std::size_t m = 0; m < c.levels.size(); ++m) {
            std::snprintf(line, sizeof line, "        level %2zu %5d px  mean %8.4f%%  p99 %8.4f%%\n", m,
                          c.levels[m].faceSize, 100.0 * c.levels[m].meanRelative,
                          100.0 * c.levels[m].p99Relative);
            text += line;
        }
    }
    return text;
}

nlohmann::json formatCostToJson(const FormatCost& cost, bool withTime) {
    nlohmann::json levels = nlohmann::json::array();
    for (const LevelStorageError& e : cost.levels)
        levels.push_back(
            {{"faceSize", e.faceSize}, {"meanRelative", e.meanRelative}, {"p99Relative", e.p99Relative}});
    nlohmann::json out = {{"format", cost.format},
                          {"fileBytes", cost.fileBytes},
                          {"gpuBytes", cost.gpuBytes},
                          {"storageScale", cost.storageScale},
                          {"levels", levels}};
    if (withTime) out["encodeSeconds"] = cost.encodeSeconds;
    return out;
}

} // namespace ibl
