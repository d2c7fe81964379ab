// The ingest pipeline: read -> repair (colour; alpha when read) -> colour-convert -> repair -> premultiply
// (unassociated alpha) -> resample into the source cube.
// Non-finite values are repaired before the colour matrix (which would smear an Inf into NaNs across
// channels); negatives are repaired on both sides of it, since a gamut change can create them.
#include "iblbake/baker/ingest.h"
#include "ingest_internal.h"

#include "iblbake/core/error.h"
#include "iblbake/core/limits.h"
#include "iblbake/core/numeric.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <optional>
#include <utility>

namespace ibl {

namespace {

using limits::kMaxFaceSize;

// A lat-long's width / 4 (its resolution at the equator) rounded to the nearest power of two.
int defaultLatLongFaceSize(int width) {
    const int target = std::max(1, width / 4);
    int p = 1;
    while (p <= target / 2)
        p *= 2;
    return std::min(kMaxFaceSize, target - p < 2 * p - target ? p : 2 * p);
}

void add(IngestReport& report, const ingest::RepairCounts& n) {
    report.nanRepaired += n.nan;
    report.infRepaired += n.inf;
    report.negativeRepaired += n.negative;
}

void add(IngestReport& report, const ingest::AlphaRepairCounts& n) {
    report.alphaNanRepaired += n.nan;
    report.alphaNegativeRepaired += n.negative;
    report.alphaOverOneRepaired += n.overOne;
}

// A single OpenEXR lat-long without alpha, resampled block by block as it is decoded (docs/performance.md
// "Big HDRIs"): the same cube and report as the whole image's, holding a few blocks of rows instead of the
// lat-long. Nothing for another input, or one with an infinity (whose repair needs the whole image).
std::optional<SourceEnvironment> ingestLatLongInBlocks(const std::filesystem::path& file,
                                                       const IngestSettings& settings) {
    ingest::OpenedImage image = ingest::openImage(
        file, [&](const ingest::RawImage& header) { ingest::resolveLayout(header, settings.layout); },
        settings.readAlpha);
    if (!image.source->readsRowsInAnyOrder() || image.alpha >= 0) return std::nullopt;
    const ingest::RawImage& raw = image.raw;
    SourceEnvironment env;
    IngestReport& report = env.report;
    report.layout = ingest::resolveLayout(raw, settings.layout);
    if (report.layout != EnvLayout::LatLong) return std::nullopt;
    report.file = raw.file;
    report.width = raw.pixels.width;
    report.height = raw.pixels.height;
    report.inputColorSpace = ingest::resolveInputColorSpace(raw, settings.inputColorSpace);
    const glm::dvec3 weights = ingest::luminanceWeights(settings.workingColorSpace); // also checks linearity
    report.workingColorSpace = ingest::colorSpaceName(settings.workingColorSpace);
    report.faceSize =
        settings.sourceFaceSize > 0 ? settings.sourceFaceSize : defaultLatLongFaceSize(raw.pixels.width);
    report.latLongPixels = ingest::resolveLatLongPixels(raw, settings.latLongPixels);
    std::function<ingest::RepairCounts(ImageRGBA&)> convertColour;
    if (!ingest::isIdentityConversion(report.inputColorSpace, report.workingColorSpace, raw.file))
        convertColour = [&](ImageRGBA& pixels) {
            return ingest::convertColorRepaired(pixels, report.inputColorSpace, report.workingColorSpace,
                                                raw.file);
        };
    ingest::RepairedLatLongBlocks blocks(image, weights, convertColour,
                                         ingest::defaultBlockPixels(raw.pixels.width));
    try {
        env.cube = ingest::resampleLatLongBlocks(blocks, report.faceSize, *report.latLongPixels,
                                                 double(settings.rotateDegrees) * kDegree);
        blocks.decodeRest();
    } catch (const ingest::NeedsWholeImage&) {
        return std::nullopt;
    }
    add(report, blocks.repairs());
    report.maxLuminanceIn = blocks.maxLuminance();
    return env;
}

} // namespace

SourceEnvironment ingestEnvironment(const std::vector<std::filesystem::path>& files,
                                    const IngestSettings& settings) {
    const bool six = settings.layout == EnvLayout::SixFiles;
    if (six && files.size() != 6)
        throw Error("layout six-files needs 6 files (+X, -X, +Y, -Y, +Z, -Z), got " +
                    std::to_string(files.size()));
    if (!six && files.size() != 1)
        throw Error("expected one input file, got " + std::to_string(files.size()) +
                    (files.size() == 6 ? " (six faces need the layout six-files)" : ""));
    if (!(std::abs(settings.rotateDegrees) <= limits::kMaxRotationDegrees))
        throw SettingError("rotateDegrees", "the rotation must be a number of degrees from -" +
                                                std::to_string(int(limits::kMaxRotationDegrees)) + " to " +
                                                std::to_string(int(limits::kMaxRotationDegrees)));
    if (settings.sourceFaceSize < 0 || settings.sourceFaceSize > kMaxFaceSize)
        throw SettingError("sourceFaceSize", "the source face size " +
                                                 std::to_string(settings.sourceFaceSize) + " is not in 0.." +
                                                 std::to_string(kMaxFaceSize));

    if (!six && settings.visibilityMask.empty())
        if (std::optional<SourceEnvironment> env = ingestLatLongInBlocks(files.front(), settings))
            return std::move(*env);

    std::vector<ingest::RawImage> images;
    // A size the layout cannot take is refused from the header, before the pixels are read. A single
    // Radiance file is kept as stored, and decoded below unless it is a lat-long that nothing changes
    // before the resampling.
    const bool keepRgbe = !six && settings.visibilityMask.empty();
    for (const auto& file : files)
        images.push_back(ingest::readImage(
            file, [&](const ingest::RawImage& header) { ingest::resolveLayout(header, settings.layout); },
            settings.readAlpha, keepRgbe));

    if (!settings.visibilityMask.empty()) {
        if (!settings.readAlpha || settings.visibilityMask.size() != files.size())
            throw SettingError("visibilityMask",
                               "needs one mask per input file (" + std::to_string(files.size()) + ")");
        for (std::size_t i = 0; i < images.size(); ++i)
            ingest::takeVisibilityMask(images[i], ingest::readImage(settings.visibilityMask[i]));
    }

    SourceEnvironment env;
    IngestReport& report = env.report;
    const ingest::RawImage& first = images.front();
    report.file = first.file;
    report.width = first.pixels.width;
    report.height = first.pixels.height;
    report.layout = ingest::resolveLayout(first, settings.layout);
    for (const auto& image : images) {
        if (image.pixels.width != first.pixels.width || image.pixels.height != first.pixels.height)
            throw Error(image.file + ": is " + std::to_string(image.pixels.width) + "x" +
                        std::to_string(image.pixels.height) + ", but " + first.file + " is " +
                        std::to_string(first.pixels.width) + "x" + std::to_string(first.pixels.height));
        ingest::resolveLayout(image, report.layout); // six files: each must be square
    }

    const double rotate = double(settings.rotateDegrees) * kDegree;
    report.inputColorSpace = ingest::resolveInputColorSpace(first, settings.inputColorSpace);
    const glm::dvec3 weights = ingest::luminanceWeights(settings.workingColorSpace); // also checks linearity
    report.workingColorSpace = ingest::colorSpaceName(settings.workingColorSpace);
    for (auto& image : images) {
        if (!image.rgbe.pixels.empty() && report.layout == EnvLayout::LatLong &&
            ingest::isIdentityConversion(report.inputColorSpace, report.workingColorSpace, image.file)) {
            // RGBE holds no NaN, Inf, negative value or alpha: nothing to repair.
            report.maxLuminanceIn =
                std::max(report.maxLuminanceIn, ingest::maxLuminance(image.rgbe, weights));
            continue;
        }
        ingest::decodeKeptRgbe(image); // nothing when none were kept
        add(report, ingest::sanitize(image.pixels));
        if (image.hasAlpha) add(report, ingest::sanitizeAlpha(image.pixels));
        add(report, ingest::convertColorRepaired(image.pixels, report.inputColorSpace,
                                                 report.workingColorSpace, image.file));
        if (image.unassociatedAlpha) ingest::premultiplyAlpha(image.pixels);
        report.maxLuminanceIn = std::max(report.maxLuminanceIn, ingest::maxLuminance(image.pixels, weights));
    }
    // A visibility of 1 everywhere is none: the capture then ingests, and bakes, as one without alpha.
    report.hasAlpha = std::any_of(images.begin(), images.end(), [](const ingest::RawImage& image) {
        return image.hasAlpha && ingest::hasAlphaBelowOne(image.pixels);
    });
    if (report.hasAlpha && report.layout != EnvLayout::LatLong && rotate != 0.0)
        throw SettingError("rotateDegrees", first.file +
                                                ": a cube-layout capture with alpha cannot be rotated "
                                                "(the rotation resamples colour only); rotate a "
                                                "lat-long capture instead");

    if (report.layout == EnvLayout::LatLong) {
        report.faceSize = settings.sourceFaceSize > 0 ? settings.sourceFaceSize
                                                      : defaultLatLongFaceSize(first.pixels.width);
        report.latLongPixels = ingest::resolveLatLongPixels(first, settings.latLongPixels);
        env.cube = first.rgbe.pixels.empty()
                       ? ingest::resampleLatLongToCubeRotated(first.pixels, report.faceSize,
                                                              *report.latLongPixels, rotate, report.hasAlpha)
                       : ingest::resampleLatLongToCubeRotated(first.rgbe, report.faceSize,
                                                              *report.latLongPixels, rotate);
    } else {
        const ingest::SourceFaces faces =
            report.layout == EnvLayout::ExrCube
                ? ingest::facesFromExrCube(first, report.hasAlpha)
                : ingest::facesFromLayout(images, report.layout, report.hasAlpha);
        report.faceSize =
            settings.sourceFaceSize > 0 ? settings.sourceFaceSize : ingest::sourceFaceSizeOf(faces);
        env.cube = ingest::resampleFacesToCube(faces, report.faceSize);
        if (rotate != 0.0) env.cube = ingest::rotateCube(env.cube, rotate);
    }
    return env;
}

} // namespace ibl
