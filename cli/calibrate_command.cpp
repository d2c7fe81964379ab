// iblbake calibrate: HDRI in, the same environment in absolute luminance (cd/m2) out as a float OpenEXR,
// optionally with the sun taken out as an analytic disk light (JSON).
//
// The work is the library's calibrateInInputLayout (iblbake/baker/environment.h), the file its
// writeCalibratedEnvironment (iblbake/baker/product_writers.h): the factor measured on the
// ingested source cube (so `calibrate` and the baking commands given the same option agree), the output in
// the input's layout where that is lossless -- a lat-long at the input's resolution, its own pixels times
// the factor, the sun taken out of those pixels; for cube inputs a vertical strip of the calibrated source
// cube, which ingest reads back exactly. The pixels are lin_rec709 (the working space, and what ingest
// assumes for a float EXR without chromaticities), so the output reads back as written.
#include "calibration_options.h"
#include "commands.h"
#include "input_options.h"

#include <iblbake/baker/environment.h>
#include <iblbake/baker/product_writers.h>
#include <iblbake/core/error.h>
#include <iblbake/ktx2/atomic_file.h>
#include <iblbake/ktx2/output_set.h>

#include <cstdio>
#include <filesystem>
#include <memory>

namespace ibl::cli {

namespace {

struct CalibrateOptions {
    OneInputOptions input;
    std::string output;
    CalibrationOptions calibration;
};

} // namespace

Action addCalibrateCommand(CLI::App& app) {
    auto o = std::make_shared<CalibrateOptions>();
    CLI::App* cmd = app.add_subcommand(
        "calibrate",
        "scale an HDRI to absolute luminance (cd/m2), optionally extracting the sun as a disk light");
    o->input.addTo(*cmd, "face size of the source cube the factor is measured on (default: from the input); "
                         "also the output's for cube inputs");
    cmd->add_option("-o,--output", o->output,
                    "output OpenEXR (float): lat-long for lat-long inputs, else a "
                    "vertical strip of cube faces")
        ->required();
    o->calibration.addTo(*cmd);

    return [o] {
        if (!o->calibration.anySource())
            throw Error("give one calibration source: --scale, --ev100, --illuminance, --sun-illuminance, "
                        "--sky-luminance or --radiometric (--scale 1 keeps the values)");
        checkOutputFile(o->output); // every output checked before any work
        if (!o->calibration.sunJson.empty()) checkOutputFile(o->calibration.sunJson);
        CalibratedImage calibrated;
        try {
            calibrated = calibrateInInputLayout(
                o->input.input, o->calibration.environmentSettings(o->input.settings(), false));
        } catch (const SettingError& e) {
            throw withFlag(e, o->calibration);
        }
        const IngestReport& r = calibrated.report;
        const ImageRGBA& image = calibrated.image;
        OutputSet outputs;
        writeCalibratedEnvironment(outputs, calibrated, o->output);
        if (!o->calibration.sunJson.empty() && calibrated.sun)
            writeSunProduct(outputs, *calibrated.sun, calibrated.record.absolute(), o->calibration.sunJson);
        outputs.commit();

        std::printf("input   %s: %dx%d %s, %s -> %s, source cube %d\n", r.file.c_str(), r.width, r.height,
                    layoutText(r).c_str(), r.inputColorSpace.c_str(), r.workingColorSpace.c_str(),
                    r.faceSize);
        std::printf("%s\n", calibrated.record.summary().c_str());
        if (calibrated.sun) {
            const DiskLight& l = *calibrated.sun;
            std::printf("sun     extracted: elevation %.2f deg, azimuth %.2f deg, angular radius %.3f deg, "
                        "E_perp %.6g %s, solid angle %.4g sr -> %s\n",
                        l.elevationDegrees(), l.azimuthDegrees(), l.angularRadiusDegrees(), l.illuminance,
                        calibrated.record.absolute() ? "lux" : "(relative)", l.solidAngle,
                        o->calibration.sunJson.c_str());
        }
        std::printf("wrote   %s: %dx%d float, %s\n", o->output.c_str(), image.width, image.height,
                    calibrated.record.units().c_str());
        return 0;
    };
}

} // namespace ibl::cli
