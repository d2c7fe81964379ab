// iblbake specular: HDRI in, prefiltered specular (LD) cube mip chain out as KTX2.
#include "calibration_options.h"
#include "commands.h"
#include "common_options.h"
#include "input_options.h"

#include <iblbake/baker/exr_output.h>
#include <iblbake/baker/ingest.h>
#include <iblbake/baker/preview.h>
#include <iblbake/baker/products.h>
#include <iblbake/baker/specular.h>
#include <iblbake/core/error.h>
#include <iblbake/core/limits.h>
#include <iblbake/ktx2/atomic_file.h>
#include <iblbake/ktx2/cube_profile.h>
#include <iblbake/ktx2/ktx2.h>
#include <iblbake/ktx2/output_set.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>

namespace ibl::cli {

namespace {

struct SpecularOptions {
    InputOptions input;
    std::string output;
    int size = 256;
    int levels = 0;
    std::string quality = "production";
    std::uint32_t samples = 0;
    std::string format = "rgba16f";
    std::string profile = "standard";
    std::string exrDir;
    std::string preview;
    std::string roughLayers;
    std::string mipMapping = "frostbite";
    float lodBias = SpecularSettings{}.lodBias;
    bool clampToFormat = false;
    BackendOptions backend;
    CalibrationOptions calibration;
};

// One EXR per level: the six faces side by side in +X, -X, +Y, -Y, +Z, -Z order (OpenGL orientation).
void writeDebugExr(const std::filesystem::path& dir, const CubeMapChain& chain, MipMapping mapping) {
    for (std::size_t m = 0; m < chain.levels.size(); ++m) {
        const CubeMap& level = chain.levels[m];
        ImageRGBA strip(6 * level.faceSize, level.faceSize);
        for (int f = 0; f < 6; ++f)
            for (int y = 0; y < level.faceSize; ++y)
                for (int x = 0; x < level.faceSize; ++x)
                    strip.at(f * level.faceSize + x, y) = level.faces[f].at(x, y);
        ExrOutputOptions exr;
        exr.channels = 3;
        exr.attributes = {{"iblbake:layout", "horizontal strip +X,-X,+Y,-Y,+Z,-Z, OpenGL face orientation"},
                          {"iblbake:level", std::to_string(m)},
                          {"iblbake:roughnessMapping", mipMappingName(mapping)},
                          {"iblbake:roughnessMappingMeaning", mipMappingMeaning(mapping)}};
        writeExr(dir / ("level_" + std::to_string(m) + ".exr"), strip, exr);
    }
}

} // namespace

Action addSpecularCommand(CLI::App& app) {
    auto o = std::make_shared<SpecularOptions>();
    CLI::App* cmd =
        app.add_subcommand("specular", "bake the prefiltered specular (LD) cube mip chain to KTX2");
    o->input.addTo(*cmd);
    cmd->add_option("-o,--output", o->output, "output .ktx2 file")->required();
    cmd->add_option("--size", o->size, "face size of level 0 (power of two)")->capture_default_str();
    cmd->add_option("--levels", o->levels, "mip levels (default: down to 1x1)")
        ->check(CLI::Range(1, mipLevelCount(limits::kMaxFaceSize)));
    cmd->add_option("--quality", o->quality, "sample preset: draft, production, reference")
        ->capture_default_str()
        ->check(CLI::IsMember({"draft", "production", "reference"}));
    cmd->add_option("--samples", o->samples, "maximum samples per texel (overrides the preset)")
        ->check(CLI::Range(1u, limits::kMaxSamples));
    cmd->add_option("--format", o->format, "rgba16f, rgba32f, b10g11r11, e5b9g9r9")
        ->capture_default_str()
        ->check(CLI::IsMember(kKtx2FormatNames));
    cmd->add_option("--profile", o->profile,
                    "cube layout for the engine: standard (OpenGL faces), three (three.js CubeTexture)")
        ->capture_default_str()
        ->check(CLI::IsMember(kCubeProfileNames));
    cmd->add_option("--exr", o->exrDir, "also write every level as OpenEXR into this directory");
    cmd->add_option("--preview", o->preview, "also write a tone-mapped PNG of every level");
    cmd->add_option(
        "--rough-layers", o->roughLayers,
        "also write the chain's rough layers (KTX2 cube map array, docs/formats.md \"Rough layers\")");
    cmd->add_option("--mip-mapping", o->mipMapping, "roughness per level: frostbite (eq. 63) or linear")
        ->capture_default_str()
        ->check(CLI::IsMember(std::vector<std::string>(kMipMappingNames.begin(), kMipMappingNames.end())));
    cmd->add_option("--lod-bias", o->lodBias, "added to the source LOD of each sample")
        ->capture_default_str();
    cmd->add_flag("--clamp-to-format", o->clampToFormat,
                  "clamp to the format's range (energy lost is reported) instead of storing with a storage "
                  "scale");
    o->backend.addTo(*cmd);
    o->calibration.addTo(*cmd);

    return [o] {
        auto start = std::chrono::steady_clock::now();
        const Ktx2Format format = parseKtx2Format(o->format);
        SpecularSettings settings;
        settings.levels = o->levels;
        settings.quality = parseQuality(o->quality);
        settings.samples = o->samples;
        settings.mapping = parseMipMapping(o->mipMapping);
        settings.lodBias = o->lodBias;
        validateSpecularSettings(settings, o->size);
        // Every output checked before any work: a bad --preview must not fail after -o was written.
        checkOutputFile(o->output);
        if (!o->preview.empty()) checkOutputFile(o->preview);
        if (!o->roughLayers.empty()) checkOutputFile(o->roughLayers);
        if (!o->exrDir.empty() && std::filesystem::exists(o->exrDir) &&
            !std::filesystem::is_directory(o->exrDir))
            throw Error(o->exrDir + ": is not a directory (--exr)");
        if (!o->exrDir.empty()) // its files, or the directory the command will make
            checkOutputFile(std::filesystem::is_directory(o->exrDir) ? o->exrDir + "/level_0.exr"
                                                                     : o->exrDir);
        if (!o->calibration.sunJson.empty()) checkOutputFile(o->calibration.sunJson);
        std::future<Executor> pendingExecutor = o->backend.startExecutor(standaloneSpecularBackend(
            parseBackend(o->backend.backend), !o->backend.device.empty(), settings, o->size));
        // The cube with the sun is kept for level 0 (below).
        PreparedEnvironment input = ingestCalibrated(o->input, o->calibration, o->size, true);
        const Executor executor = pendingExecutor.get();
        const SourceEnvironment& env = input.env;
        const PreparedEnvironment& calibration = input;
        const double ingestMs = millisecondsSince(start);
        const IngestReport& r = env.report;

        std::vector<SpecularLevelTiming> timings;
        auto bakeStart = std::chrono::steady_clock::now();
        SpecularWithRoughLayers baked;
        if (o->roughLayers.empty()) // the ingested cube becomes level 0, moved rather than copied
            baked.chain = bakeSpecular(std::move(input.env.cube), settings, executor, &timings);
        else
            baked = bakeSpecularWithRoughLayers(env.cube, settings, executor, &timings);
        CubeMapChain& chain = baked.chain;
        const double bakeMs = millisecondsSince(bakeStart);
        for (const SpecularLevelTiming& t : timings)
            std::printf("level %2d  r=%.4f  %4d px  %8.2f ms\n", t.level, t.perceptualRoughness,
                        chain.levels[std::size_t(t.level)].faceSize, t.milliseconds);

        const int levelCount = int(chain.levels.size());
        LdChainProduct ld;
        ld.mapping = settings.mapping;
        ld.levelCount = levelCount;
        ld.colorSpace = r.workingColorSpace;
        ld.source = std::filesystem::path(r.file).filename().string();
        ld.latLongPixels = r.latLongPixels;
        ld.settings = "quality=" + o->quality + " samples=" + std::to_string(samplesFor(settings)) +
                      " lodBias=" + std::to_string(settings.lodBias) + " size=" + std::to_string(o->size) +
                      " rotate=" + std::to_string(o->input.rotateDegrees);
        ld.sunInLevel0 =
            calibration.withSun && keepSunInLevel0(chain, *calibration.withSun, format, o->clampToFormat);
        ld.sunMaxSolidAngle = o->calibration.sunMaxSolidAngle;
        Ktx2KeyValues kv = ldChainKeyValues(ld, calibration.record, calibration.sun);
        kv.emplace_back(kCubeProfileKey, o->profile);
        const ProductStorage storage = chooseProductStorage(chain, format, o->clampToFormat);
        OutputSet outputs; // all of them or none: a failed --preview leaves no -o
        Ktx2WriteStats stats;
        outputs.writeFile(o->output, [&](const std::filesystem::path& temporary) {
            stats = writeProductCube(temporary, chain, format, kv, storage);
        });
        writeSunJson(outputs, o->calibration, calibration.record, calibration.sun);
        if (!o->exrDir.empty())
            outputs.writeDirectory(o->exrDir, [&](const std::filesystem::path& temporary) {
                writeDebugExr(temporary, chain, settings.mapping);
            });
        if (!o->preview.empty())
            outputs.writeFile(o->preview, [&](const std::filesystem::path& temporary) {
                writeChainPreview(temporary, chain);
            });
        std::optional<ProductStorage> roughStorage;
        if (!o->roughLayers.empty()) {
            const std::vector<CubeMap>& layers = baked.roughLayers;
            roughStorage = chooseProductStorage(CubeMapChain{layers}, format, o->clampToFormat);
            Ktx2KeyValues roughKv = roughLayerKeyValues(ld, calibration.record, calibration.sun);
            roughKv.emplace_back(kCubeProfileKey, o->profile);
            outputs.writeFile(o->roughLayers, [&](const std::filesystem::path& temporary) {
                writeProductCubeArray(temporary, layers, format, roughKv, *roughStorage);
            });
        }
        outputs.commit();
        BackendOptions::storeBuiltKernels(executor);
        std::printf("wrote   %s: %d levels, %s, %llu clamped texels, %llu repaired non-finite\n",
                    o->output.c_str(), levelCount, o->format.c_str(), (unsigned long long)stats.clampedTexels,
                    (unsigned long long)stats.repairedNonFinite);
        printStorage(o->output, o->format, storage);
        if (roughStorage) {
            std::printf("wrote   %s: %u rough layers of %u px (r = %s)\n", o->roughLayers.c_str(),
                        IBL_ROUGH_LAYER_COUNT, roughLayerFaceSize(std::uint32_t(o->size)),
                        roughLayerRoughnessText().c_str());
            printStorage(o->roughLayers, o->format, *roughStorage);
        }
        std::printf("time    ingest %.1f ms, bake %.1f ms (%s), total %.1f ms\n", ingestMs, bakeMs,
                    executor.description().c_str(), millisecondsSince(start));
        o->backend.printTiming(executor, "specular", bakeMs);
        return 0;
    };
}

} // namespace ibl::cli
