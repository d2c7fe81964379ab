// iblbake preview BAKE_DIR: material balls (perceptual roughness 0..1 across, a dielectric and a metal
// row) lit by a bake through the runtime module; with --reference, the brute-force render of the same
// balls against the original environment beside it and a relative-error heat map.
#include "calibration_options.h"
#include "commands.h"
#include "common_options.h"
#include "input_options.h"

#include <iblbake/baker/calibration.h>
#include <iblbake/baker/exr_output.h>
#include <iblbake/baker/ingest.h>
#include <iblbake/baker/preview.h>
#include <iblbake/baker/products.h>
#include <iblbake/baker/sun.h>
#include <iblbake/core/error.h>
#include <iblbake/ktx2/ktx2.h>
#include <iblbake/runtime/runtime.h>
#include <iblbake/runtime/runtime_manifest.h>
#include <iblbake/runtime/runtime_reference.h>

#include <OpenImageIO/imageio.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>

namespace fs = std::filesystem;

namespace ibl::cli {
namespace {

constexpr int kColumns = 11; // perceptual roughness 0, 0.1, ..., 1
constexpr int kRows = 2;     // dielectric, metal

struct PreviewOptions {
    std::string bakeDir;
    std::string output;
    std::string reference;
    std::string latLongPixels = "auto"; // of the reference, as the bake read it
    float exposure = 0.0f;
    int sphereSize = 96;
    BackendOptions backend;
};

ImageRGBA readDfgLut(const fs::path& path) {
    auto in = OIIO::ImageInput::open(path.string());
    if (!in) throw Error(path.string() + ": " + OIIO::geterror());
    const OIIO::ImageSpec& spec = in->spec();
    ImageRGBA lut(spec.width, spec.height);
    std::vector<float> pixels(std::size_t(spec.width) * spec.height * spec.nchannels);
    if (spec.nchannels < 3 || !in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, pixels.data()))
        throw Error(path.string() + ": not a DFG LUT (needs R, G, B)");
    for (std::size_t i = 0; i < lut.pixels.size(); ++i)
        lut.pixels[i] = glm::vec4(pixels[i * spec.nchannels], pixels[i * spec.nchannels + 1],
                                  pixels[i * spec.nchannels + 2], 1.0f);
    return lut;
}

// The "iblbake.calibration.factor" value of a bake's KTX2: a finite, positive number and nothing else.
double calibrationFactorFrom(const std::string& text, const fs::path& file) {
    double factor = 0.0;
    const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), factor);
    if (error != std::errc() || end != text.data() + text.size() || !std::isfinite(factor) || factor <= 0.0)
        throw Error(file.string() + ": iblbake.calibration.factor " + quotedForMessage(text) +
                    " is not a positive number");
    return factor;
}

// The probe set of a bake directory as the README's first command writes it.
ProbeSet loadLooseBake(const fs::path& dir) {
    LdPyramid ld = loadLdKtx2(dir / "specular.ktx2");
    DfgTable dfg = dfgTableFromImage(readDfgLut(dir / "dfg_lut.exr"));
    nlohmann::json diffuse;
    try {
        diffuse = nlohmann::json::parse(readText(dir / "diffuse.json"));
    } catch (const nlohmann::json::exception& e) {
        throw Error((dir / "diffuse.json").string() + ": " + e.what());
    }
    std::array<glm::vec3, 9> irradiance{};
    const auto& coefficients = diffuse.at("sh").at("irradiance");
    if (coefficients.size() != 9)
        throw Error((dir / "diffuse.json").string() + ": sh.irradiance needs 9 entries");
    for (int i = 0; i < 9; ++i)
        irradiance[i] = glm::vec3(coefficients[i][0].get<float>(), coefficients[i][1].get<float>(),
                                  coefficients[i][2].get<float>());
    ProbeSet set(std::move(ld), std::move(dfg), shCoefficientsFrom(irradiance, false));
    if (fs::exists(dir / "sun.json")) set.setSun(sunDiskFrom(diskLightFromJson(readText(dir / "sun.json"))));
    if (fs::exists(dir / "irradiance.ktx2"))
        set.setIrradianceCube(loadIrradianceKtx2(dir / "irradiance.ktx2"));
    return set;
}

struct LoadedBake {
    ProbeSet set;
    RuntimeOptions options;
    double calibrationFactor = 1.0;
};

// A scene bake (`iblbake bake`) through its manifest.json, else the loose files of the README's first
// command, whose calibration factor is recorded in specular.ktx2.
LoadedBake loadBake(const fs::path& dir) {
    if (fs::exists(dir / "manifest.json")) {
        ManifestProbeSet m = loadProbeSetFromManifest(dir / "manifest.json");
        return {std::move(m.set), m.options, m.calibrationFactor};
    }
    LoadedBake bake{loadLooseBake(dir), RuntimeOptions{}, 1.0};
    Ktx2Image ktx = readKtx2(dir / "specular.ktx2");
    if (auto it = ktx.keyValues.find("iblbake.calibration.factor"); it != ktx.keyValues.end())
        bake.calibrationFactor = calibrationFactorFrom(it->second, dir / "specular.ktx2");
    return bake;
}

// One shading point per sphere pixel (orthographic camera on +Z looking down -Z, +Y up); pixels off
// the spheres are left out and marked in `owner` with -1.
std::vector<ShadingPoint> spherePoints(int size, std::vector<int>& owner) {
    const int width = kColumns * size, height = kRows * size;
    owner.assign(std::size_t(width) * height, -1);
    std::vector<ShadingPoint> points;
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            int column = x / size, row = y / size;
            float u = (float(x % size) + 0.5f) / float(size) * 2.0f - 1.0f;
            float v = 1.0f - (float(y % size) + 0.5f) / float(size) * 2.0f;
            float rr = (u * u + v * v) / 0.81f; // radius 0.9 of the cell
            if (rr >= 1.0f) continue;
            ShadingPoint p{};
            p.normal = glm::vec3(u / 0.9f, v / 0.9f, std::sqrt(1.0f - rr));
            p.view = glm::vec3(0.0f, 0.0f, 1.0f);
            p.baseColor = row == 0 ? glm::vec3(0.8f) : glm::vec3(0.95f, 0.93f, 0.88f);
            p.metallic = row == 0 ? 0.0f : 1.0f;
            p.perceptualRoughness = float(column) / float(kColumns - 1);
            p.ao = 1.0f;
            owner[std::size_t(y) * width + x] = int(points.size());
            points.push_back(p);
        }
    return points;
}

float luminance(const glm::vec3& c) {
    return 0.2126f * c.x + 0.7152f * c.y + 0.0722f * c.z;
}

// 0 black, 5% blue, 10% yellow, 20% and more red.
glm::vec3 heat(float relativeError) {
    float t = std::clamp(relativeError / 0.2f, 0.0f, 1.0f);
    if (t < 0.25f) return glm::mix(glm::vec3(0.0f), glm::vec3(0.1f, 0.2f, 1.0f), t / 0.25f);
    if (t < 0.5f)
        return glm::mix(glm::vec3(0.1f, 0.2f, 1.0f), glm::vec3(1.0f, 1.0f, 0.1f), (t - 0.25f) / 0.25f);
    return glm::mix(glm::vec3(1.0f, 1.0f, 0.1f), glm::vec3(1.0f, 0.05f, 0.05f), (t - 0.5f) / 0.5f);
}

} // namespace

Action addPreviewCommand(CLI::App& app) {
    auto o = std::make_shared<PreviewOptions>();
    CLI::App* cmd =
        app.add_subcommand("preview", "render material balls lit by a bake (and the reference beside it)");
    cmd->add_option("bake", o->bakeDir,
                    "bake directory: manifest.json (iblbake bake), else specular.ktx2, dfg_lut.exr, "
                    "diffuse.json [, sun.json] [, irradiance.ktx2: diffuse from it instead of the SH]")
        ->required();
    cmd->add_option("-o,--output", o->output, "output PNG; the linear render goes to the same name with .exr")
        ->required();
    cmd->add_option("--reference", o->reference,
                    "the HDRI the bake came from: add the brute-force render and the error heat map");
    addLatLongPixelsOption(*cmd, o->latLongPixels);
    cmd->add_option("--exposure", o->exposure, "exposure compensation in stops")->capture_default_str();
    cmd->add_option("--sphere-size", o->sphereSize, "pixels per ball")
        ->capture_default_str()
        ->check(CLI::Range(8, 512));
    o->backend.addTo(*cmd);

    return [o] {
        auto start = std::chrono::steady_clock::now();
        if (fs::path(o->output).extension() != ".png")
            throw Error(o->output + ": the preview is written as .png");
        LoadedBake bake = loadBake(o->bakeDir);
        const ProbeSet& set = bake.set;
        std::vector<int> owner;
        std::vector<ShadingPoint> points = spherePoints(o->sphereSize, owner);
        Executor executor = o->backend.makeExecutor();
        std::vector<glm::vec4> shaded;
        if (executor.usesOpenCL()) {
            OpenCLProbeEvaluator evaluator(executor.cl(), set);
            shaded = evaluator.evaluate(points, bake.options);
        } else {
            shaded = evaluateCpu(set, points, bake.options);
        }

        std::vector<glm::vec3> reference;
        if (!o->reference.empty()) {
            // The same calibration as the bake, the full map (sun included), at the bake's mirror
            // resolution (at least 128): a coarser reference would blur what the runtime's level 0 shows
            // sharply and count it as the runtime's error.
            const double factor = bake.calibrationFactor;
            IngestSettings ingest;
            ingest.sourceFaceSize = std::max(128, int(set.distantLd().layout.baseFaceSize));
            ingest.latLongPixels = parseLatLongPixels(o->latLongPixels);
            SourceEnvironment env = ingestEnvironment({fs::path(o->reference)}, ingest);
            applyCalibration(env.cube, factor);
            ReferenceSettings settings;
            settings.samplesPerStrategy = 256; // a picture, not a measurement: tests use 2048
            settings.albedoSamples = 1024;
            for (const ReferenceResult& r :
                 renderReference(ReferenceLighting::distant(env.cube), points, bake.options, settings))
                reference.push_back(glm::vec3(r.total()));
        }

        const int width = kColumns * o->sphereSize, height = kRows * o->sphereSize;
        const int panels = reference.empty() ? 1 : 3;
        ImageRGBA image(panels * width, height);
        double sumLuminance = 0.0;
        for (const glm::vec4& c : shaded)
            sumLuminance += luminance(glm::vec3(c));
        const float scale =
            float(0.18 * points.size() / std::max(sumLuminance, 1e-12)) * std::exp2(o->exposure);
        std::vector<double> columnError(kColumns, 0.0), columnReference(kColumns, 0.0);
        for (int y = 0; y < height; ++y)
            for (int x = 0; x < width; ++x) {
                int k = owner[std::size_t(y) * width + x];
                if (k < 0) continue;
                glm::vec3 c(shaded[std::size_t(k)]);
                image.at(x, y) = glm::vec4(c, 1.0f);
                if (reference.empty()) continue;
                glm::vec3 r = reference[std::size_t(k)];
                image.at(width + x, y) = glm::vec4(r, 1.0f);
                float error = std::abs(luminance(c) - luminance(r)) / std::max(luminance(r), 1e-12f);
                // The heat map is display-referred: divide by the tone scale so it shows as drawn.
                image.at(2 * width + x, y) = glm::vec4(heat(error) / scale, 1.0f);
                columnError[std::size_t(x / o->sphereSize)] += std::abs(luminance(c) - luminance(r));
                columnReference[std::size_t(x / o->sphereSize)] += luminance(r);
            }
        writeTonemappedPng(o->output, image, scale);
        ExrOutputOptions exr;
        exr.channels = 3;
        exr.attributes = {
            {"iblbake:preview", reference.empty() ? "runtime" : "runtime | reference | error heat map"}};
        fs::path exrPath = fs::path(o->output).replace_extension(".exr");
        writeExr(exrPath, image, exr);
        std::printf("wrote   %s and %s (%d x %d, %s)\n", o->output.c_str(), exrPath.c_str(), image.width,
                    image.height, executor.description().c_str());
        if (!reference.empty()) {
            std::printf("error   relative mean per roughness column (luminance, both rows):");
            for (int c = 0; c < kColumns; ++c)
                std::printf(" %.1f%%", 100.0 * columnError[c] / columnReference[c]);
            std::printf("\n");
        }
        std::printf("time    %.1f ms\n", millisecondsSince(start));
        return 0;
    };
}

} // namespace ibl::cli
