// iblbake format-cost CHAIN.ktx2 [--formats a,b,...] [--json]: what storing a baked chain in each format
// costs (iblbake/baker/format_cost.h); the chain is best given in rgba32f, the reference the errors are
// measured against.
#include "commands.h"

#include <iblbake/baker/format_cost.h>
#include <iblbake/core/error.h>
#include <iblbake/core/temporary_path.h>
#include <iblbake/ktx2/storage_scale.h>

#include <nlohmann/json.hpp>

#include <cstdio>
#include <memory>

namespace ibl::cli {
namespace {

struct FormatCostOptions {
    std::string chain;
    std::vector<std::string> formats = kKtx2FormatNames;
    bool json = false;
};

} // namespace

Action addFormatCostCommand(CLI::App& app) {
    auto o = std::make_shared<FormatCostOptions>();
    CLI::App* cmd = app.add_subcommand(
        "format-cost",
        "file bytes, GPU bytes, encode time and error per level of a baked chain in each format");
    cmd->add_option("chain", o->chain, "a baked LD chain (KTX2), the float reference (best rgba32f)")
        ->required();
    cmd->add_option("--formats", o->formats, "the formats to measure (default: all)")
        ->delimiter(',')
        ->check(CLI::IsMember(kKtx2FormatNames));
    cmd->add_flag("--json", o->json, "one JSON document instead of text");

    return [o] {
        Ktx2Image image = readKtx2(o->chain);
        if (image.faceCount != 6 || image.layerCount != 0) throw Error(o->chain + ": not a cube map chain");
        unscaleKtx2Texels(image);
        CubeMapChain chain;
        for (std::vector<ImageRGBA>& faces : image.levels) {
            CubeMap level;
            level.faceSize = faces.front().width;
            for (std::size_t f = 0; f < 6; ++f)
                level.faces[f] = std::move(faces[f]);
            chain.levels.push_back(std::move(level));
        }
        const std::filesystem::path scratch =
            temporaryPathBeside(std::filesystem::temp_directory_path() / "iblbake-format-cost");
        std::filesystem::create_directories(scratch);
        std::vector<FormatCost> costs;
        try {
            for (const std::string& name : o->formats)
                costs.push_back(measureFormatCost(chain, parseKtx2Format(name), scratch));
        } catch (...) {
            std::error_code ignored;
            std::filesystem::remove_all(scratch, ignored);
            throw;
        }
        std::error_code ignored;
        std::filesystem::remove_all(scratch, ignored);
        if (o->json) {
            nlohmann::json out = {{"chain", o->chain}, {"formats", nlohmann::json::array()}};
            for (const FormatCost& c : costs)
                out["formats"].push_back(formatCostToJson(c, true));
            std::printf("%s\n", out.dump(2).c_str());
        } else {
            std::printf("%s", formatCostText(costs, true).c_str());
        }
        return 0;
    };
}

} // namespace ibl::cli
