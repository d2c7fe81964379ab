// The material preview's render (iblbake/baker/material_preview.h): the balls' shading points, the runtime
// and brute-force renders, the per-column error, and the linear panels as OpenEXR.
#include "iblbake/baker/material_preview.h"
#include "iblbake/core/numeric.h"

#include "iblbake/baker/exr_output.h"
#include "iblbake/runtime/runtime_reference.h"
#include "preview_grid.h"

#include <algorithm>
#include <cmath>

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

MaterialPreview renderMaterialPreview(const ProbeSet& set, const RuntimeOptions& options,
                                      const CubeMap* referenceCube, const Executor& executor,
                                      const MaterialPreviewSettings& settings,
                                      const std::filesystem::path& png, const std::filesystem::path& exr) {
    const int size = settings.sphereSize;
    std::vector<int> owner;
    const std::vector<ShadingPoint> points =
        previewBallPoints(size, kPreviewColumns, kRows, owner, [](ShadingPoint& p, int row, int column) {
            p.baseColor = row == 0 ? glm::vec3(0.8f) : glm::vec3(0.95f, 0.93f, 0.88f);
            p.metallic = row == 0 ? 0.0f : 1.0f;
            p.perceptualRoughness = float(column) / float(kPreviewColumns - 1);
        });
    std::vector<glm::vec4> shaded;
    if (executor.usesOpenCL()) {
        OpenCLProbeEvaluator evaluator(executor.cl(), set);
        shaded = evaluator.evaluate(points, options);
    } else {
        shaded = evaluateCpu(set, points, options);
    }
    std::vector<glm::vec3> reference, check; // check: the reference's error estimate
    MaterialPreview out;
    if (referenceCube) {
        ConvergedReferenceSettings rs;
        rs.samples = settings.referenceSamples;
        const ConvergedReference converged = renderConvergedReference(*referenceCube, points, options, rs);
        for (std::size_t k = 0; k < points.size(); ++k) {
            reference.push_back(glm::vec3(converged.results[k].total()));
            check.push_back(glm::vec3(converged.errorEstimate[k]));
        }
        out.referenceBrightTexels = converged.brightTexels;
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

} // namespace ibl
