// `iblbake specular`'s flow (product_flows.h): bake the chain, then write it and its extra outputs.
#include "iblbake/baker/preview.h"
#include "iblbake/baker/product_flows.h"
#include "iblbake/core/error.h"
#include "iblbake/ktx2/atomic_file.h"
#include "wall_time.h"

namespace ibl {

namespace fs = std::filesystem;

namespace {

// iblbake.settings of a standalone chain: what decided its texels, as the command was given them.
std::string settingsText(const SpecularJob& job) {
    return std::string("quality=") + qualityName(job.settings.quality) +
           " samples=" + std::to_string(samplesFor(job.settings)) +
           " lodBias=" + std::to_string(job.settings.lodBias) + " size=" + std::to_string(job.faceSize) +
           " rotate=" + std::to_string(job.rotateDegrees);
}

} // namespace

void checkSpecularOutputs(const SpecularJob& job) {
    checkOutputFile(job.chain);
    if (!job.preview.empty()) checkOutputFile(job.preview);
    if (!job.roughLayers.empty()) checkOutputFile(job.roughLayers);
    if (!job.exrDirectory.empty()) {
        if (fs::exists(job.exrDirectory) && !fs::is_directory(job.exrDirectory))
            throw Error(job.exrDirectory.string() + ": is not a directory (--exr)");
        // Its files, or the directory the flow will make.
        checkOutputFile(fs::is_directory(job.exrDirectory) ? job.exrDirectory / "level_0.exr"
                                                           : job.exrDirectory);
    }
    if (!job.sunJson.empty()) checkOutputFile(job.sunJson);
}

SpecularProducts bakeSpecularProducts(PreparedEnvironment input, const SpecularJob& job,
                                      const Executor& executor, const StageTimed& timed) {
    const IngestReport report = input.env.report;
    SpecularProducts products;
    SpecularWithRoughLayers baked;
    products.bakeMilliseconds = wallMilliseconds([&] {
        if (job.roughLayers.empty()) // the ingested cube becomes level 0, moved rather than copied
            baked.chain = bakeSpecular(std::move(input.env.cube), job.settings, executor, &products.timings);
        else
            baked = bakeSpecularWithRoughLayers(input.env.cube, job.settings, executor, &products.timings);
    });
    if (timed) timed("specular", products.bakeMilliseconds);
    for (const CubeMap& level : baked.chain.levels)
        products.levelFaceSizes.push_back(level.faceSize);

    LdChainWriteSettings write;
    write.product.mapping = job.settings.mapping;
    write.product.levelCount = int(baked.chain.levels.size());
    write.product.colorSpace = report.workingColorSpace;
    write.product.source = fs::path(report.file).filename().string();
    write.product.latLongPixels = report.latLongPixels;
    write.product.settings = settingsText(job);
    write.product.sunMaxSolidAngle = job.sunMaxSolidAngle;
    write.format = job.format;
    write.clampToFormat = job.clampToFormat;
    write.profile = job.profile;
    write.withSun = input.withSun ? &*input.withSun : nullptr;

    OutputSet outputs; // all of them or none: a failed --preview leaves no chain
    products.written =
        writeLdChainProduct(outputs, baked, write, input.record, input.sun, job.chain, job.roughLayers);
    if (!job.sunJson.empty() && input.sun)
        writeSunProduct(outputs, *input.sun, input.record.absolute(), job.sunJson);
    if (!job.exrDirectory.empty())
        writeLdChainExrLevels(outputs, baked.chain, job.settings.mapping, job.exrDirectory);
    if (!job.preview.empty())
        outputs.writeFile(job.preview,
                          [&](const fs::path& temporary) { writeChainPreview(temporary, baked.chain); });
    outputs.commit();
    return products;
}

} // namespace ibl
