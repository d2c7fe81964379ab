// The material preview's render (iblbake/baker/material_preview.h): the balls' shading points, the runtime
// and brute-force renders, the per-column error, and the linear panels as OpenEXR.
#include "iblbake/baker/material_preview.h"
#include "iblbake/core/numeric.h"

#include "iblbake/baker/exr_output.h"
#include "iblbake/baker/products.h"
#include "iblbake/core/error.h"
#include "iblbake/core/format_text.h"
#include "iblbake/ktx2/atomic_file.h"
#include "iblbake/runtime/runtime_reference.h"
#include "preview_grid.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>

namespace ibl {

namespace {

constexpr int kRows = 2; // dielectric, metal

std::vector<double> ratios(const std::vector<double>& error, const std::vector<double>& reference) {
    std::vector<double> out(error.size());
    for (std::size_t i = 0; i < error.size(); ++i)
        out[i] = error[i] / std::max(reference[i], 1e-30);
    return out;
}

} // namespace

glm::vec3 previewErrorColor(float relativeError) {
    float t = std::clamp(relativeError / 0.2f, 0.0f, 1.0f);
    if (t < 0.25f) return glm::mix(glm::vec3(0.0f), glm::vec3(0.1f, 0.2f, 1.0f), t / 0.25f);
    if (t < 0.5f)
        return glm::mix(glm::vec3(0.1f, 0.2f, 1.0f), glm::vec3(1.0f, 1.0f, 0.1f), (t - 0.25f) / 0.25f);
    return glm::mix(glm::vec3(1.0f, 1.0f, 0.1f), glm::vec3(1.0f, 0.05f, 0.05f), (t - 0.5f) / 0.5f);
}

namespace {

// The balls: dielectric (row 0) and metal (row 1), perceptual roughness c / 10 in column c.
std::vector<ShadingPoint> materialBallPoints(int size, std::vector<int>& owner) {
    return previewBallPoints(size, kPreviewColumns, kRows, owner, [](ShadingPoint& p, int row, int column) {
        p.baseColor = row == 0 ? glm::vec3(0.8f) : glm::vec3(0.95f, 0.93f, 0.88f);
        p.metallic = row == 0 ? 0.0f : 1.0f;
        p.perceptualRoughness = float(column) / float(kPreviewColumns - 1);
    });
}

constexpr char kReferenceMagic[8] = {'I', 'B', 'L', 'R', 'E', 'F', '1', '\n'};

} // namespace

std::vector<ShadingPoint> materialPreviewPoints(int sphereSize, std::vector<int>& ballOfPoint) {
    std::vector<int> owner;
    std::vector<ShadingPoint> points = materialBallPoints(sphereSize, owner);
    ballOfPoint.assign(points.size(), 0);
    const std::size_t width = std::size_t(kPreviewColumns * sphereSize);
    for (std::size_t i = 0; i < owner.size(); ++i)
        if (owner[i] >= 0)
            ballOfPoint[std::size_t(owner[i])] =
                int(i / width) / sphereSize * kPreviewColumns + int(i % width) / sphereSize;
    return points;
}

PreviewReference renderPreviewReference(const CubeMap& environment, const RuntimeOptions& options,
                                        const MaterialPreviewSettings& settings,
                                        const ReferenceProgress& progress) {
    std::vector<int> column;
    const std::vector<ShadingPoint> points = materialPreviewPoints(settings.sphereSize, column);
    for (int& c : column)
        c %= kPreviewColumns;
    AdaptiveReferenceSettings adaptive;
    adaptive.targetError = settings.referenceTargetError;
    const AdaptiveReference r =
        renderAdaptiveReference(environment, points, column, options, {}, adaptive, progress);
    PreviewReference out;
    for (std::size_t k = 0; k < points.size(); ++k) {
        out.value.push_back(glm::vec3(r.reference.results[k].total()));
        out.errorEstimate.push_back(glm::vec3(r.reference.errorEstimate[k]));
    }
    out.brightTexels = r.reference.brightTexels;
    out.columnSamples = r.groupSamples;
    out.columnErrorEstimate = r.groupErrorEstimate;
    return out;
}

void writePreviewReference(const std::filesystem::path& binary, const std::filesystem::path& facts,
                           const PreviewReference& reference) {
    const std::uint32_t count = std::uint32_t(reference.value.size());
    std::string bytes(kReferenceMagic, sizeof kReferenceMagic);
    bytes.append(reinterpret_cast<const char*>(&count), sizeof count);
    for (const std::vector<glm::vec3>* values : {&reference.value, &reference.errorEstimate})
        bytes.append(reinterpret_cast<const char*>(values->data()), values->size() * sizeof(glm::vec3));
    writeFileBytes(binary, bytes);
    const nlohmann::json document = {{"brightTexels", reference.brightTexels},
                                     {"columnSamples", reference.columnSamples},
                                     {"columnErrorEstimate", reference.columnErrorEstimate}};
    writeFileBytes(facts, document.dump(2) + '\n');
}

PreviewReference readPreviewReference(const std::filesystem::path& binary, const std::filesystem::path& facts,
                                      int sphereSize) {
    std::vector<int> owner;
    const std::size_t count = materialBallPoints(sphereSize, owner).size();
    const std::string bytes = readText(binary);
    std::uint32_t stored = 0;
    if (bytes.size() >= sizeof kReferenceMagic + sizeof stored)
        std::memcpy(&stored, bytes.data() + sizeof kReferenceMagic, sizeof stored);
    if (bytes.compare(0, sizeof kReferenceMagic, kReferenceMagic, sizeof kReferenceMagic) != 0 ||
        stored != count ||
        bytes.size() != sizeof kReferenceMagic + sizeof stored + 2 * count * sizeof(glm::vec3))
        throw Error(binary.string() + ": not a preview reference of " + std::to_string(count) + " points");
    PreviewReference out;
    out.value.resize(count);
    out.errorEstimate.resize(count);
    const char* data = bytes.data() + sizeof kReferenceMagic + sizeof stored;
    std::memcpy(out.value.data(), data, count * sizeof(glm::vec3));
    std::memcpy(out.errorEstimate.data(), data + count * sizeof(glm::vec3), count * sizeof(glm::vec3));
    try {
        const nlohmann::json document = nlohmann::json::parse(readText(facts));
        out.brightTexels = document.at("brightTexels").get<std::size_t>();
        out.columnSamples = document.at("columnSamples").get<std::vector<std::uint32_t>>();
        out.columnErrorEstimate = document.at("columnErrorEstimate").get<std::vector<double>>();
    } catch (const nlohmann::json::exception& e) {
        throw Error(facts.string() + ": " + e.what());
    }
    return out;
}

MaterialPreview renderMaterialPreview(const ProbeSet& set, const RuntimeOptions& options,
                                      const CubeMap* referenceCube, const Executor& executor,
                                      const MaterialPreviewSettings& settings,
                                      const std::filesystem::path& png, const std::filesystem::path& exr) {
    if (!referenceCube)
        return renderMaterialPreview(set, options, static_cast<const PreviewReference*>(nullptr), executor,
                                     settings, png, exr);
    const PreviewReference reference = renderPreviewReference(*referenceCube, options, settings);
    return renderMaterialPreview(set, options, &reference, executor, settings, png, exr);
}

MaterialPreview renderMaterialPreview(const ProbeSet& set, const RuntimeOptions& options,
                                      const PreviewReference* previewReference, const Executor& executor,
                                      const MaterialPreviewSettings& settings,
                                      const std::filesystem::path& png, const std::filesystem::path& exr) {
    const int size = settings.sphereSize;
    std::vector<int> owner;
    const std::vector<ShadingPoint> points = materialBallPoints(size, owner);
    std::vector<glm::vec4> shaded;
    if (executor.usesOpenCL()) {
        OpenCLProbeEvaluator evaluator(executor.cl(), set);
        shaded = evaluator.evaluate(points, options);
    } else {
        shaded = evaluateCpu(set, points, options);
    }
    std::vector<glm::vec3> reference, check; // check: the reference's error estimate
    MaterialPreview out;
    if (previewReference) {
        if (previewReference->value.size() != points.size())
            throw Error("material preview: a reference of " + std::to_string(previewReference->value.size()) +
                        " points for " + std::to_string(points.size()));
        reference = previewReference->value;
        check = previewReference->errorEstimate;
        out.referenceBrightTexels = previewReference->brightTexels;
    }

    // The panels: runtime | reference | error (each kPreviewColumns x kRows balls).
    const int width = kPreviewColumns * size, height = kRows * size;
    const int panels = reference.empty() ? 1 : 3;
    ImageRGBA image(panels * width, height);
    double sumLuminance = 0.0;
    for (const glm::vec4& c : shaded)
        sumLuminance += rec709Luminance(glm::vec3(c));
    const float scale =
        float(0.18 * points.size() / std::max(sumLuminance, 1e-12)) * std::exp2(settings.exposureEV);
    std::vector<double> error[kRows], referenceSum[kRows], referenceError[kRows];
    for (int r = 0; r < kRows; ++r)
        error[r].assign(kPreviewColumns, 0.0), referenceSum[r].assign(kPreviewColumns, 0.0),
            referenceError[r].assign(kPreviewColumns, 0.0);
    std::vector<glm::vec3> errorColor(points.size(), glm::vec3(0.0f));
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            int k = owner[std::size_t(y) * width + x];
            if (k < 0) continue;
            glm::vec3 c(shaded[std::size_t(k)]);
            image.at(x, y) = glm::vec4(c, 1.0f);
            if (reference.empty()) continue;
            glm::vec3 r = reference[std::size_t(k)];
            image.at(width + x, y) = glm::vec4(r, 1.0f);
            float relative =
                std::abs(rec709Luminance(c) - rec709Luminance(r)) / std::max(rec709Luminance(r), 1e-12f);
            errorColor[std::size_t(k)] = previewErrorColor(relative);
            // The heat map is display-referred: divide by the tone scale so it shows as drawn.
            image.at(2 * width + x, y) = glm::vec4(errorColor[std::size_t(k)] / scale, 1.0f);
            error[y / size][std::size_t(x / size)] += std::abs(rec709Luminance(c) - rec709Luminance(r));
            referenceSum[y / size][std::size_t(x / size)] += rec709Luminance(r);
            referenceError[y / size][std::size_t(x / size)] += rec709Luminance(check[std::size_t(k)]);
        }

    for (int c = 0; c < kPreviewColumns; ++c)
        out.roughness.push_back(float(c) / float(kPreviewColumns - 1));
    if (!reference.empty()) {
        out.dielectricError = ratios(error[0], referenceSum[0]);
        out.metalError = ratios(error[1], referenceSum[1]);
        out.dielectricReferenceError = ratios(referenceError[0], referenceSum[0]);
        out.metalReferenceError = ratios(referenceError[1], referenceSum[1]);
        std::vector<double> both(kPreviewColumns), bothReference(kPreviewColumns), bothCheck(kPreviewColumns);
        for (std::size_t c = 0; c < std::size_t(kPreviewColumns); ++c) {
            both[c] = error[0][c] + error[1][c];
            bothReference[c] = referenceSum[0][c] + referenceSum[1][c];
            bothCheck[c] = referenceError[0][c] + referenceError[1][c];
        }
        out.error = ratios(both, bothReference);
        out.referenceError = ratios(bothCheck, bothReference);
    }

    const PreviewLayout layout = previewLayout(size, !reference.empty());
    PreviewGridLabels labels;
    labels.roughness = out.roughness;
    labels.groups = {"dielectric", "metal"};
    labels.error = {out.dielectricError, out.metalError};
    labels.referenceError = {out.dielectricReferenceError, out.metalReferenceError};
    writePreviewGrid(png, layout, image, errorColor, owner, scale, labels);
    out.width = layout.width;
    out.height = layout.height;

    ExrOutputOptions exrOptions;
    exrOptions.channels = 3;
    exrOptions.attributes = {
        {"iblbake:preview", reference.empty() ? "runtime" : "runtime | reference | error heat map"}};
    writeExr(exr, image, exrOptions);
    return out;
}

std::string materialPreviewErrorText(const MaterialPreview& preview) {
    if (preview.error.empty()) return "";
    std::string text = "error   relative mean per roughness column (luminance, both rows):";
    for (double e : preview.error)
        text += formatText(" %.1f%%", 100.0 * e);
    text += formatText("\nreference's own estimated error per column (%zu bright texels integrated exactly):",
                       preview.referenceBrightTexels);
    for (double e : preview.referenceError)
        text += formatText(" %.2f%%", 100.0 * e);
    return text + "\n";
}

} // namespace ibl
