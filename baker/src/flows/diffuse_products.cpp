// `iblbake diffuse`'s flow (product_flows.h): the SH, the optional irradiance cube, the document.
#include "iblbake/baker/product_flows.h"
#include "iblbake/core/format_text.h"
#include "iblbake/ktx2/atomic_file.h"
#include "wall_time.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace ibl {

namespace fs = std::filesystem;

namespace {

// The document's "irradianceCube": what was written and how.
nlohmann::json cubeEntry(const IrradianceCubeJob& job, const std::string& methodText,
                         const DiffuseProducts& p) {
    nlohmann::json entry = {{"file", job.file.string()},
                            {"faceSize", job.settings.faceSize},
                            {"format", job.formatName},
                            {"method", irradianceMethodName(job.method)},
                            {"methodDetail", methodText},
                            {"normalization", kIrradianceNormalization},
                            {"clampedTexels", p.cube->stats.clampedTexels},
                            {"shNegativeTexels", p.shNegativeTexels}};
    entry.update(productStorageToJson(p.cube->storage));
    if (job.method == IrradianceMethod::Sampled) entry["samples"] = irradianceSamplesFor(job.settings);
    return entry;
}

} // namespace

std::string shWindowText(const ShWindowResult& w, int faceSize) {
    auto percent = [&](const glm::dvec3& v) { // the worst channel, relative to its mean irradiance
        double worst = std::numeric_limits<double>::infinity();
        for (int c = 0; c < 3; ++c)
            if (w.meanIrradiance[c] > 0.0) worst = std::min(worst, v[c] / w.meanIrradiance[c]);
        return std::isfinite(worst) ? 100.0 * worst : 0.0;
    };
    std::string text = formatText("sh      L2 from %d px faces; window %s", faceSize, shWindowName(w.window));
    if (w.window != ShWindow::None)
        text += formatText(" %s=%.6g", w.window == ShWindow::Sloan ? "lambda" : "w", w.parameter);
    text += formatText(" (%s), band factors %.4f %.4f\n", w.searched ? "searched" : "given", w.factors[1],
                       w.factors[2]);
    return text + formatText("        min irradiance before %.6g %.6g %.6g, after %.6g %.6g %.6g "
                             "(worst channel: %.3f%% -> %.3f%% of its mean)\n",
                             w.minBefore.x, w.minBefore.y, w.minBefore.z, w.minAfter.x, w.minAfter.y,
                             w.minAfter.z, percent(w.minBefore), percent(w.minAfter));
}

std::string diffuseProductsText(const DiffuseJob& job, const DiffuseProducts& products, int sourceFaceSize) {
    std::string text = shWindowText(products.sh.window, sourceFaceSize);
    if (products.cube) {
        const IrradianceCubeJob& c = *job.cube;
        text += formatText("cube    %d px %s, %s: %.1f ms, %llu clamped texels, %llu SH-negative texels\n",
                           c.settings.faceSize, irradianceMethodName(c.method), c.formatName.c_str(),
                           products.cubeMilliseconds, (unsigned long long)products.cube->stats.clampedTexels,
                           (unsigned long long)products.shNegativeTexels);
        text += storageText(c.file, c.formatName, products.cube->storage);
    }
    return text + formatText("wrote   %s%s%s\n", job.document.string().c_str(), job.cube ? " and " : "",
                             job.cube ? job.cube->file.string().c_str() : "");
}

void checkDiffuseOutputs(const DiffuseJob& job) {
    checkOutputFile(job.document);
    if (job.cube) checkOutputFile(job.cube->file);
    if (!job.sunJson.empty()) checkOutputFile(job.sunJson);
}

DiffuseProducts bakeDiffuseProducts(const PreparedEnvironment& input, const DiffuseJob& job,
                                    const Executor& executor, const StageTimed& timed) {
    const SourceEnvironment& env = input.env;
    const IngestReport& r = env.report;
    DiffuseProducts products;
    products.shMilliseconds = wallMilliseconds([&] { products.sh = bakeDiffuseSH(env.cube, job.window); });
    if (timed) timed("sh-projection", products.shMilliseconds);

    OutputSet outputs;
    nlohmann::json extra;
    if (job.cube) {
        const IrradianceCubeJob& c = *job.cube;
        CubeMap cube;
        products.cubeMilliseconds = wallMilliseconds([&] {
            cube = c.method == IrradianceMethod::Sampled
                       ? bakeIrradianceCube(env.cube, c.settings, executor)
                       : irradianceCubeFromSH(products.sh.irradiance, c.settings.faceSize,
                                              &products.shNegativeTexels);
        });
        IrradianceCubeWriteSettings write;
        write.methodText = irradianceMethodText(c.method, irradianceSamplesFor(c.settings));
        write.colorSpace = r.workingColorSpace;
        write.source = fs::path(r.file).filename().string();
        write.latLongPixels = r.latLongPixels;
        write.format = parseKtx2Format(c.formatName);
        write.clampToFormat = c.clampToFormat;
        write.profile = c.profile;
        products.cube =
            writeIrradianceCubeProduct(outputs, std::move(cube), write, input.record, input.sun, c.file);
        extra["irradianceCube"] = cubeEntry(c, write.methodText, products);
        if (timed) timed("irradiance-cube", products.cubeMilliseconds);
    }
    const DiffuseSource source{r.file,
                               r.width,
                               r.height,
                               layoutName(r.layout),
                               r.inputColorSpace,
                               env.cube.faceSize,
                               job.rotateDegrees,
                               r.latLongPixels};
    extra["timing"] = {{"ingestMs", job.ingestMilliseconds},
                       {"shMs", products.shMilliseconds},
                       {"irradianceCubeMs", products.cubeMilliseconds}};
    writeDiffuseProduct(outputs, products.sh, job.requestedWindow, r.workingColorSpace, source, input.record,
                        input.sun, job.document, extra);
    if (!job.sunJson.empty() && input.sun)
        writeSunProduct(outputs, *input.sun, input.record.absolute(), job.sunJson);
    outputs.commit();
    return products;
}

} // namespace ibl
