// Environment preparation (iblbake/baker/environment.h): ingest, calibration, sun extraction.
#include "iblbake/baker/environment.h"

#include "iblbake/core/error.h"

#include <utility>

namespace ibl {

namespace {

// Errors of the steps after ingest, prefixed with the input file as ingest's own are; a SettingError stays
// one, so that the caller can still name the setting.
template <class Step>
auto namingFile(const std::string& file, Step&& step) {
    try {
        return step();
    } catch (const SettingError& e) {
        throw SettingError(e.setting(), file + ": " + e.what());
    } catch (const Error& e) {
        throw Error(file + ": " + e.what());
    }
}

// The extraction's detection: the calibration's detection settings with the working space's weights and
// the extraction's own size limit.
SunDetectSettings extractionDetection(const EnvironmentSettings& settings, const glm::dvec3& weights) {
    SunDetectSettings detection = settings.calibration.sun;
    detection.luminanceWeights = weights;
    detection.maxSolidAngle = settings.sunMaxSolidAngle;
    return detection;
}

ImageRGBA verticalStrip(const CubeMap& cube) {
    const int n = cube.faceSize;
    ImageRGBA strip(n, 6 * n);
    for (int f = 0; f < 6; ++f)
        for (int y = 0; y < n; ++y)
            for (int x = 0; x < n; ++x)
                strip.at(x, f * n + y) = cube.faces[std::size_t(f)].at(x, y);
    return strip;
}

} // namespace

std::optional<DiskLight> takeSunOut(SphereTexels& texels, SunExtraction mode,
                                    const SunDetectSettings& detection) {
    if (mode == SunExtraction::Keep) return std::nullopt;
    const SunDetection sun = detectSun(texels, detection);
    if (!sun.found) {
        if (mode == SunExtraction::IfDetected) return std::nullopt;
        throw SettingError("extractSun", "no sun detected: " + sun.reason);
    }
    return extractSun(texels, sun, detection.luminanceWeights);
}

std::optional<DiskLight> takeSunOut(CubeMap& cube, SunExtraction mode, const SunDetectSettings& detection) {
    SphereTexels texels(cube);
    return takeSunOut(texels, mode, detection);
}

PreparedEnvironment prepareEnvironment(SourceEnvironment env, const EnvironmentSettings& settings) {
    PreparedEnvironment out{std::move(env), {}, {}, {}};
    CubeMap& cube = out.env.cube;
    const glm::dvec3 weights = workingLuminanceWeights(out.env.report.workingColorSpace);
    CalibrationSettings calibration = settings.calibration;
    calibration.luminanceWeights = weights;
    namingFile(out.env.report.file, [&] {
        out.record = computeCalibration(cube, calibration);
        applyCalibration(cube, out.record.factor);
        if (settings.keepCubeWithSun && settings.sun != SunExtraction::Keep) out.withSun = cube;
        out.sun = takeSunOut(cube, settings.sun, extractionDetection(settings, weights));
        if (!out.sun) out.withSun.reset();
    });
    return out;
}

PreparedEnvironment prepareEnvironment(const std::vector<std::filesystem::path>& files,
                                       const EnvironmentSettings& settings) {
    return prepareEnvironment(ingestEnvironment(files, settings.ingest), settings);
}

CalibratedImage calibrateInInputLayout(const std::filesystem::path& file,
                                       const EnvironmentSettings& settings) {
    SourceEnvironment env = ingestEnvironment({file}, settings.ingest);
    CalibratedImage out;
    out.latLong = env.report.layout == EnvLayout::LatLong;
    EnvironmentSettings cubeSettings = settings;
    cubeSettings.keepCubeWithSun = false;
    if (out.latLong) cubeSettings.sun = SunExtraction::Keep; // taken out of the lat-long pixels below
    PreparedEnvironment prepared = prepareEnvironment(std::move(env), cubeSettings);
    out.report = prepared.env.report;
    out.record = prepared.record;
    if (!out.latLong) {
        out.image = verticalStrip(prepared.env.cube);
        out.sun = prepared.sun;
        return out;
    }
    IngestSettings ingest = settings.ingest;
    ingest.layout = EnvLayout::LatLong;
    out.image = readWorkingLatLong(file, ingest);
    applyCalibration(out.image, out.record.factor);
    const glm::dvec3 weights = workingLuminanceWeights(out.report.workingColorSpace);
    SphereTexels texels(out.image, *out.report.latLongPixels); // the placement the cube was ingested with
    out.sun = namingFile(out.report.file, [&] {
        return takeSunOut(texels, settings.sun, extractionDetection(settings, weights));
    });
    return out;
}

} // namespace ibl
