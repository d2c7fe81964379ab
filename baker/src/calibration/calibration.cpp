// Calibration factor from one known quantity (the sources are described in iblbake/baker/calibration.h).
#include "iblbake/baker/calibration.h"

#include "../ingest/ingest_internal.h"
#include "iblbake/core/error.h"
#include "iblbake/core/numeric.h"

#include <tbb/parallel_for.h>

#include <cmath>
#include <cstdio>
#include <limits>

namespace ibl {

namespace {

// The source's value cannot be used on this environment (calibration.h).
SettingError unusable(const std::string& problem) {
    return SettingError("calibration", problem);
}

} // namespace

const char* calibrationSourceName(CalibrationSource source) {
    switch (source) {
    case CalibrationSource::Scale:
        return "scale";
    case CalibrationSource::Ev100:
        return "ev100";
    case CalibrationSource::Illuminance:
        return "illuminance";
    case CalibrationSource::SunIlluminance:
        return "sun-illuminance";
    case CalibrationSource::SkyLuminance:
        return "sky-luminance";
    case CalibrationSource::Radiometric:
        return "radiometric";
    default:
        return "none";
    }
}

std::string CalibrationRecord::summary() const {
    std::string text = std::string("calibration ") + calibrationSourceName(source);
    if (source != CalibrationSource::None && source != CalibrationSource::Radiometric) {
        text += ' '; // appended apart: GCC 12 warns (-Wrestrict) on " " + std::string&&
        text += floatDecimal(sourceValue);
    }
    char buf[256];
    std::snprintf(buf, sizeof buf, ": factor %.6g, %s %.6g -> %.6g", factor, quantity.c_str(), measuredBefore,
                  measuredAfter);
    return text + buf + " (" + units() + ")";
}

CalibrationRecord computeCalibration(const SphereTexels& texels, const CalibrationSettings& settings) {
    const CalibrationSource source = settings.source;
    const double value = settings.value;
    const bool needsValue = source != CalibrationSource::None && source != CalibrationSource::Radiometric;
    if (needsValue && !std::isfinite(value)) throw unusable("the value must be a finite number");
    if (needsValue && source != CalibrationSource::Ev100 && !(value > 0.0))
        throw unusable("the value must be positive, got " + floatDecimal(value));

    CalibrationRecord rec;
    rec.source = source;
    rec.sourceValue = needsValue ? value : 0.0;
    const EnvironmentTotals stats = computeEnvironmentTotals(texels, settings.luminanceWeights);
    rec.upwardIlluminanceBefore = stats.upwardIlluminance;
    rec.meanLuminanceBefore = stats.meanLuminance;
    rec.quantity = "mean luminance";
    rec.measuredBefore = stats.meanLuminance;

    SunDetection sun;
    if (source == CalibrationSource::SunIlluminance || source == CalibrationSource::SkyLuminance) {
        SunDetectSettings sunSettings = settings.sun;
        sunSettings.luminanceWeights = settings.luminanceWeights;
        sun = detectSun(texels, sunSettings);
        rec.sunMeasured = true;
        rec.sunFound = sun.found;
        rec.sunIlluminanceBefore = sun.found ? sun.light.illuminance : 0.0;
    }

    switch (source) {
    case CalibrationSource::None:
        rec.factor = 1.0;
        break;
    case CalibrationSource::Scale:
        rec.factor = value;
        break;
    case CalibrationSource::Ev100:
        if (std::fabs(value) > 64.0) throw unusable(floatDecimal(value) + " is not an EV100 in -64..64");
        rec.factor = 1.2 * std::exp2(value);
        break;
    case CalibrationSource::Radiometric:
        rec.factor = kLuminousEfficacy;
        break;
    case CalibrationSource::Illuminance:
        rec.quantity = "upward illuminance";
        rec.measuredBefore = stats.upwardIlluminance;
        if (!(stats.upwardIlluminance > 0.0))
            throw unusable("the environment sends no light to an upward-facing surface");
        rec.factor = value / stats.upwardIlluminance;
        break;
    case CalibrationSource::SunIlluminance:
        rec.quantity = "sun illuminance (perpendicular)";
        if (!sun.found) throw unusable("no sun detected: " + sun.reason);
        rec.measuredBefore = sun.light.illuminance;
        rec.factor = value / sun.light.illuminance;
        break;
    case CalibrationSource::SkyLuminance: {
        rec.quantity = "zenith luminance";
        // A spot meter is pointed at the sky, not at the sun: the sun's texels are left out.
        rec.measuredBefore =
            zenithLuminance(texels, kZenithCapDegrees, settings.luminanceWeights, sun.region);
        if (!(rec.measuredBefore > 0.0)) throw unusable("the zenith of the environment is black");
        rec.factor = value / rec.measuredBefore;
        break;
    }
    }
    if (!std::isfinite(rec.factor) || !(rec.factor > 0.0))
        throw unusable("the calibration factor " + floatDecimal(rec.factor) +
                       " is not a positive finite number");
    // A channel is at most its luminance over its weight: the brightest texel scaled must stay a finite fp32
    // value (calibrate --scale 1e308 made nearly every value Inf).
    const double minWeight =
        std::min({settings.luminanceWeights.x, settings.luminanceWeights.y, settings.luminanceWeights.z});
    const double brightestChannel = stats.maxLuminance / minWeight;
    if (minWeight > 0.0 && !(rec.factor * brightestChannel <= double(std::numeric_limits<float>::max())))
        throw unusable("the calibration factor " + floatDecimal(rec.factor) +
                       " would take the brightest texel (" + floatDecimal(brightestChannel) +
                       ") beyond the largest float, " + floatDecimal(std::numeric_limits<float>::max()));
    rec.measuredAfter = rec.factor * rec.measuredBefore;
    rec.upwardIlluminanceAfter = rec.factor * rec.upwardIlluminanceBefore;
    rec.meanLuminanceAfter = rec.factor * rec.meanLuminanceBefore;
    rec.sunIlluminanceAfter = rec.factor * rec.sunIlluminanceBefore;
    return rec;
}

CalibrationRecord computeCalibration(const CubeMap& cube, const CalibrationSettings& settings) {
    return computeCalibration(SphereTexels(cube), settings);
}

void applyCalibration(ImageRGBA& image, double factor) {
    const float f = float(factor);
    tbb::parallel_for(std::size_t(0), image.pixels.size(), [&](std::size_t i) {
        glm::vec4& p = image.pixels[i];
        p = glm::vec4(glm::vec3(p) * f, p.w);
    });
}

void applyCalibration(CubeMap& cube, double factor) {
    for (ImageRGBA& face : cube.faces)
        applyCalibration(face, factor);
}

std::vector<std::pair<std::string, std::string>> calibrationMetadata(const CalibrationRecord& r,
                                                                     const std::string& prefix) {
    const std::string c = prefix + "calibration.";
    std::vector<std::pair<std::string, std::string>> kv = {
        {c + "factor", floatDecimal(r.factor)},
        {c + "source", calibrationSourceName(r.source)},
        {c + "sourceValue", floatDecimal(r.sourceValue)},
        {c + "quantity", r.quantity},
        {c + "measuredBefore", floatDecimal(r.measuredBefore)},
        {c + "measuredAfter", floatDecimal(r.measuredAfter)},
        {c + "upwardIlluminanceBefore", floatDecimal(r.upwardIlluminanceBefore)},
        {c + "upwardIlluminanceAfter", floatDecimal(r.upwardIlluminanceAfter)},
        {c + "meanLuminanceBefore", floatDecimal(r.meanLuminanceBefore)},
        {c + "meanLuminanceAfter", floatDecimal(r.meanLuminanceAfter)}};
    if (r.sunMeasured) {
        kv.emplace_back(c + "sunIlluminanceBefore", floatDecimal(r.sunIlluminanceBefore));
        kv.emplace_back(c + "sunIlluminanceAfter", floatDecimal(r.sunIlluminanceAfter));
    }
    kv.emplace_back(prefix + "units", r.units());
    return kv;
}

std::vector<std::pair<std::string, std::string>> readCalibrationMetadata(const std::filesystem::path& file) {
    std::vector<std::pair<std::string, std::string>> kv, attributes;
    try {
        attributes = ingest::readStringAttributes(file);
    } catch (const Error&) {
        return kv; // absent metadata is not a failure here: the caller reads the pixels and reports that
    }
    for (auto& [name, value] : attributes)
        if (name.rfind("iblbake:calibration.", 0) == 0 || name == "iblbake:units" ||
            name.rfind("iblbake:sun", 0) == 0)
            kv.emplace_back(std::move(name), std::move(value));
    return kv;
}

glm::dvec3 workingLuminanceWeights(const std::string& workingColorSpace) {
    const glm::dvec3 w = ingest::luminanceWeights(workingColorSpace); // also checks the space
    // lin_rec709: the customary 4-digit weights (docs/conventions.md, SOURCES.md), within 1e-4 of the matrix
    // row.
    return ingest::colorSpaceName(workingColorSpace) == ingest::colorSpaceName("lin_rec709")
               ? kRec709Luminance
               : w;
}

ImageRGBA readWorkingLatLong(const std::filesystem::path& file, const IngestSettings& settings,
                             IngestReport* report) {
    // The layout from the header: a file that is no lat-long is refused before its pixels are read.
    ingest::RawImage raw = ingest::readImage(file, [&](const ingest::RawImage& header) {
        const EnvLayout layout = ingest::resolveLayout(header, settings.layout);
        if (layout != EnvLayout::LatLong)
            throw Error(header.file + ": is a " + layoutName(layout) + " environment, not a lat-long");
    });
    IngestReport r;
    r.file = raw.file;
    r.width = raw.pixels.width;
    r.height = raw.pixels.height;
    r.layout = EnvLayout::LatLong; // checked from the header
    if (settings.rotateDegrees != 0.0f) throw Error(raw.file + ": rotation is not supported here");
    r.latLongPixels = ingest::resolveLatLongPixels(raw, settings.latLongPixels);
    r.inputColorSpace = ingest::resolveInputColorSpace(raw, settings.inputColorSpace);
    const glm::dvec3 weights = ingest::luminanceWeights(settings.workingColorSpace);
    r.workingColorSpace = ingest::colorSpaceName(settings.workingColorSpace);
    auto add = [&](const ingest::RepairCounts& n) {
        r.nanRepaired += n.nan;
        r.infRepaired += n.inf;
        r.negativeRepaired += n.negative;
    };
    add(ingest::sanitize(raw.pixels));
    add(ingest::convertColorRepaired(raw.pixels, r.inputColorSpace, r.workingColorSpace, raw.file));
    r.maxLuminanceIn = ingest::maxLuminance(raw.pixels, weights);
    if (report) *report = r;
    return std::move(raw.pixels);
}

} // namespace ibl
