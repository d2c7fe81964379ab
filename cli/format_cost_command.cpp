// iblbake format-cost CHAIN.ktx2 [--formats a,b,...] [--json]: what storing a baked chain in each format
// costs (iblbake/baker/format_cost.h); the chain is best given in rgba32f, the reference the errors are
// measured against.
#include "commands.h"

#include <iblbake/baker/format_cost.h>

#include <cstdio>

namespace ibl::cli {
namespace {

struct FormatCostOptions {
    std::string chain;
    std::vector<std::string> formats = kKtx2FormatNames;
    bool json = false;
};

} // namespace

Action addFormatCostCommand(CLI::App& app) {
    auto [o, cmd] = addSubcommand<FormatCostOptions>(
        app, "format-cost",
        "file bytes, GPU bytes, encode time and error per level of a baked chain in each format");
    cmd->add_option("chain", o->chain, "a baked LD chain (KTX2), the float reference (best rgba32f)")
        ->required();
    cmd->add_option("--formats", o->formats, "the formats to measure (default: all)")
        ->delimiter(',')
        ->check(CLI::IsMember(kKtx2FormatNames));
    cmd->add_flag("--json", o->json, "one JSON document instead of text");

    return [o = o] {
        const std::vector<FormatCost> costs = measureChainFormatCosts(o->chain, o->formats);
        std::printf("%s", o->json ? (formatCostsJson(o->chain, costs).dump(2) + "\n").c_str()
                                  : formatCostText(costs, true).c_str());
        return 0;
    };
}

} // namespace ibl::cli
