// `iblbake calibrate`'s flow and report (iblbake/baker/calibrate_file.h).
#include "iblbake/baker/calibrate_file.h"

#include "iblbake/baker/inspect.h"
#include "iblbake/baker/product_writers.h"
#include "iblbake/core/format_text.h"
#include "iblbake/ktx2/atomic_file.h"
#include "iblbake/ktx2/output_set.h"

namespace ibl {

namespace fs = std::filesystem;

CalibratedImage calibrateToFiles(const fs::path& input, const EnvironmentSettings& settings,
                                 const fs::path& output, const fs::path& sunJson) {
    checkOutputFile(output);
    checkOutputExtension(output, ".exr");
    if (!sunJson.empty()) {
        checkOutputFile(sunJson);
        checkOutputExtension(sunJson, ".json");
    }
    CalibratedImage calibrated = calibrateInInputLayout(input, settings);
    OutputSet outputs;
    writeCalibratedEnvironment(outputs, calibrated, output);
    if (!sunJson.empty() && calibrated.sun)
        writeSunProduct(outputs, *calibrated.sun, calibrated.record.absolute(), sunJson);
    outputs.commit();
    return calibrated;
}

std::string calibrateRunText(const CalibratedImage& calibrated, const fs::path& output,
                             const fs::path& sunJson) {
    const IngestReport& r = calibrated.report;
    std::string text =
        formatText("input   %s: %dx%d %s, %s -> %s, source cube %d\n", r.file.c_str(), r.width, r.height,
                   layoutText(r).c_str(), r.inputColorSpace.c_str(), r.workingColorSpace.c_str(), r.faceSize);
    text += calibrated.record.summary() + "\n";
    if (calibrated.sun) {
        const DiskLight& l = *calibrated.sun;
        text += formatText(
            "sun     extracted: elevation %.2f deg, azimuth %.2f deg, angular radius %.3f deg, "
            "E_perp %.6g %s, solid angle %.4g sr -> %s\n",
            l.elevationDegrees(), l.azimuthDegrees(), l.angularRadiusDegrees(), l.illuminance,
            calibrated.record.absolute() ? "lux" : "(relative)", l.solidAngle, sunJson.string().c_str());
    }
    return text + formatText("wrote   %s: %dx%d float, %s\n", output.string().c_str(), calibrated.image.width,
                             calibrated.image.height, calibrated.record.units().c_str());
}

} // namespace ibl
