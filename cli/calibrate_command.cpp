// iblbake calibrate: HDRI in, the same environment in absolute luminance (cd/m2) out as a float OpenEXR,
// optionally with the sun taken out as an analytic disk light (JSON).
//
// The flow is the library's (iblbake/baker/calibrate_file.h calibrateToFiles): the factor measured on the
// ingested source cube (so `calibrate` and the baking commands given the same option agree), the output in
// the input's layout where that is lossless -- a lat-long at the input's resolution, its own pixels times
// the factor, the sun taken out of those pixels; for cube inputs a vertical strip of the calibrated source
// cube, which ingest reads back exactly. The pixels are lin_rec709 (the working space, and what ingest
// assumes for a float EXR without chromaticities), so the output reads back as written.
#include "calibration_options.h"
#include "commands.h"
#include "input_options.h"

#include <iblbake/baker/calibrate_file.h>
#include <iblbake/core/error.h>

#include <cstdio>

namespace ibl::cli {

namespace {

struct CalibrateOptions {
    OneInputOptions input;
    std::string output;
    CalibrationOptions calibration;
};

} // namespace

Action addCalibrateCommand(CLI::App& app) {
    auto [o, cmd] = addSubcommand<CalibrateOptions>(
        app, "calibrate",
        "scale an HDRI to absolute luminance (cd/m2), optionally extracting the sun as a disk light");
    o->input.addTo(*cmd, "face size of the source cube the factor is measured on (default: from the input); "
                         "also the output's for cube inputs");
    cmd->add_option("-o,--output", o->output,
                    "output OpenEXR (float): lat-long for lat-long inputs, else a "
                    "vertical strip of cube faces")
        ->required();
    o->calibration.addTo(*cmd);

    return [o = o] {
        if (!o->calibration.anySource())
            throw Error("give one calibration source: --scale, --ev100, --illuminance, --sun-illuminance, "
                        "--sky-luminance or --radiometric (--scale 1 keeps the values)");
        CalibratedImage calibrated;
        try {
            calibrated =
                calibrateToFiles(o->input.input, o->calibration.environmentSettings(o->input.settings()),
                                 o->output, o->calibration.sunJson);
        } catch (const SettingError& e) {
            throw withFlag(e, o->calibration);
        }
        std::printf("%s", calibrateRunText(calibrated, o->output, o->calibration.sunJson).c_str());
        return 0;
    };
}

} // namespace ibl::cli
