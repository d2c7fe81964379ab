// iblbake calibrate: HDRI in, the same environment in absolute luminance (cd/m2) out as a float OpenEXR,
// optionally with the sun taken out as an analytic disk light (JSON).
//
// The work is the library's calibrateInInputLayout (iblbake/baker/environment.h): the factor measured on the
// ingested source cube (so `calibrate` and the baking commands given the same option agree), the output in
// the input's layout where that is lossless -- a lat-long at the input's resolution, its own pixels times
// the factor, the sun taken out of those pixels; for cube inputs a vertical strip of the calibrated source
// cube, which ingest reads back exactly. The pixels are lin_rec709 (the working space, and what ingest
// assumes for a float EXR without chromaticities), so the output reads back as written.
#include "calibration_options.h"
#include "commands.h"
#include "input_options.h"

#include <iblbake/baker/calibration.h>
#include <iblbake/baker/environment.h>
#include <iblbake/baker/exr_output.h>
#include <iblbake/baker/ingest.h>
#include <iblbake/baker/products.h>
#include <iblbake/core/error.h>
#include <iblbake/core/limits.h>
#include <iblbake/ktx2/atomic_file.h>
#include <iblbake/ktx2/output_set.h>

#include <cstdio>
#include <filesystem>
#include <memory>

namespace ibl::cli {

namespace {

struct CalibrateOptions {
    std::string input;
    std::string output;
    int size = 0;
    std::string layout = "auto";
    std::string inputColorSpace;
    std::string latLongPixels = "auto";
    CalibrationOptions calibration;
};

} // namespace

Action addCalibrateCommand(CLI::App& app) {
    auto o = std::make_shared<CalibrateOptions>();
    CLI::App* cmd = app.add_subcommand(
        "calibrate",
        "scale an HDRI to absolute luminance (cd/m2), optionally extracting the sun as a disk light");
    cmd->add_option("input", o->input, "HDR environment")->required();
    cmd->add_option("-o,--output", o->output,
                    "output OpenEXR (float): lat-long for lat-long inputs, else a "
                    "vertical strip of cube faces")
        ->required();
    cmd->add_option("--size", o->size,
                    "face size of the source cube the factor is measured on (default: from the input); also "
                    "the output's for cube inputs")
        ->check(CLI::Range(0, limits::kMaxFaceSize));
    cmd->add_option("--layout", o->layout, "auto, latlong, exr-cube, hcross, vcross, hstrip, vstrip")
        ->capture_default_str();
    cmd->add_option("--input-colorspace", o->inputColorSpace,
                    "input colour space (default: file metadata, else lin_rec709; sRGB for 8-bit files)");
    addLatLongPixelsOption(*cmd, o->latLongPixels);
    o->calibration.addTo(*cmd);

    return [o] {
        if (!o->calibration.anySource())
            throw Error("give one calibration source: --scale, --ev100, --illuminance, --sun-illuminance, "
                        "--sky-luminance or --radiometric (--scale 1 keeps the values)");
        checkOutputFile(o->output); // every output checked before any work
        if (!o->calibration.sunJson.empty()) checkOutputFile(o->calibration.sunJson);
        CalibratedImage calibrated;
        try {
            IngestSettings ingest;
            ingest.layout = parseLayout(o->layout);
            ingest.inputColorSpace = o->inputColorSpace;
            ingest.sourceFaceSize = o->size;
            ingest.latLongPixels = parseLatLongPixels(o->latLongPixels);
            calibrated = calibrateInInputLayout(o->input, o->calibration.environmentSettings(ingest, false));
        } catch (const SettingError& e) {
            throw withFlag(e, o->calibration);
        }
        const IngestReport& r = calibrated.report;
        const ImageRGBA& image = calibrated.image;
        const std::string layoutDescription =
            calibrated.latLong
                ? "latlong (DESIGN.md / OpenEXR LatLongMap: +Y first scanline, +Z at the centre, +X at u = "
                  "0.25)"
                : "vstrip: faces +X, -X, +Y, -Y, +Z, -Z stacked vertically, OpenGL face orientation";

        ExrOutputOptions exr;
        exr.channels = 3;
        exr.pixelType = PixelType::Float;
        exr.attributes = {{"iblbake:product", "calibrated-environment"},
                          {"iblbake:layout", layoutDescription},
                          {"iblbake:colorSpace", r.workingColorSpace},
                          {"iblbake:source", std::filesystem::path(r.file).filename().string()},
                          {"iblbake:version", IBLBAKE_VERSION},
                          {"Software", "iblbake " IBLBAKE_VERSION}};
        for (auto& kv : latLongPixelsKeyValues(r.latLongPixels, "iblbake:"))
            exr.attributes.push_back(std::move(kv));
        // A lat-long output keeps the input's pixel grid: OpenEXR's placement is what the envmap attribute
        // says, so that ingest reads the file back the same way.
        if (calibrated.latLong && r.latLongPixels == LatLongPixels::OpenExr) exr.envmap = ExrEnvmap::LatLong;
        for (auto& kv : calibrationKeyValues(calibrated.record, calibrated.sun, "iblbake:"))
            exr.attributes.push_back(std::move(kv));

        OutputSet outputs;
        outputs.writeFile(o->output,
                          [&](const std::filesystem::path& temporary) { writeExr(temporary, image, exr); });
        writeSunJson(outputs, o->calibration, calibrated.record, calibrated.sun);
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
