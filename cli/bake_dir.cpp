// Reading the files of a bake directory (cli/bake_dir.h).
#include "bake_dir.h"

#include <iblbake/core/error.h>

#include <nlohmann/json.hpp>

#include <cmath>

namespace fs = std::filesystem;

namespace ibl::cli {

ShRgb readPrescaledIrradiance(const fs::path& path) {
    try {
        const nlohmann::json doc = nlohmann::json::parse(readText(path));
        const nlohmann::json& c = doc.at("sh").at("irradiance");
        if (!c.is_array() || c.size() != 9) throw Error(path.string() + ": sh.irradiance needs 9 entries");
        ShRgb sh{};
        for (std::size_t i = 0; i < 9; ++i) {
            if (!c[i].is_array() || c[i].size() != 3)
                throw Error(path.string() + ": sh.irradiance[" + std::to_string(i) + "] needs 3 numbers");
            for (std::size_t k = 0; k < 3; ++k) {
                sh[i][int(k)] = c[i][k].get<double>();
                if (!std::isfinite(sh[i][int(k)]))
                    throw Error(path.string() + ": sh.irradiance[" + std::to_string(i) + "] is not finite");
            }
        }
        return sh;
    } catch (const nlohmann::json::exception& e) {
        throw Error(path.string() + ": " + e.what());
    }
}

} // namespace ibl::cli
