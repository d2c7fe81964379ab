// iblbake inspect: what an HDRI holds, photometrically (environment_stats.h, sun.h). Measured on the
// ingested source cube (exact per-texel solid angles), as every baking command sees the input.
//
// --json prints the library's document (iblbake/baker/inspect.h inspectionJson).
#include "commands.h"
#include "input_options.h"

#include <iblbake/baker/inspect.h>

#include <cstdio>

namespace ibl::cli {

namespace {

struct InspectOptions {
    OneInputOptions input;
    bool json = false;
};

} // namespace

Action addInspectCommand(CLI::App& app) {
    auto [o, cmd] = addSubcommand<InspectOptions>(
        app, "inspect", "print an HDRI's luminance statistics, upward illuminance, suggested EV100 and sun");
    o->input.addTo(*cmd, "face size of the source cube measured (default: from the input)");
    cmd->add_flag("--json", o->json, "print one JSON object (schema in iblbake/baker/inspect.h)");

    return [o = o] {
        const EnvironmentInspection inspection = inspectEnvironment(o->input.input, o->input.settings());
        std::printf("%s", o->json ? (inspectionJson(inspection).dump(2) + "\n").c_str()
                                  : inspectionText(inspection).c_str());
        return 0;
    };
}

} // namespace ibl::cli
