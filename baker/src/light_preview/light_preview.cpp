// The light preview (iblbake/baker/light_preview.h): the balls lit by each area-light shape and by a
// textured rectangle, the runtime against the fp64 brute force, drawn as the material preview's grid.
#include "iblbake/baker/light_preview.h"
#include "iblbake/core/format_text.h"
#include "iblbake/core/numeric.h"

#include "../preview/preview_grid.h"
#include "iblbake/baker/exr_output.h"
#include "iblbake/baker/light_card.h"
#include "iblbake/core/error.h"

#include <algorithm>
#include <cmath>

namespace ibl {

namespace {

constexpr int kColumns = 10; // perceptual roughness 0.1 ... 1: the mirror needs a brute force per texel
constexpr float kLumens = 1000.0f;

// The light's centre in ball space: above, left and in front of the ball, facing it, at `distance`.
glm::vec3 lightCenter(float distance) {
    return distance * glm::normalize(glm::vec3(-0.45f, 0.55f, 1.0f));
}

struct PreviewLight {
    std::string name;
    AreaLight light;
    bool textured = false;
};

std::vector<PreviewLight> previewLights(float distance, float cardAspect) {
    const glm::vec3 center = lightCenter(distance), normal = -glm::normalize(center);
    const glm::vec3 tangent = glm::normalize(glm::cross(glm::vec3(0.0f, 1.0f, 0.0f), normal));
    const glm::vec3 white(1.0f);
    // Each one light size (sqrt of its area): the sphere's and the disk's cross-section pi r^2 = 1.
    const float radius = 1.0f / std::sqrt(3.14159265f);
    const float cardWidth = std::sqrt(cardAspect), cardHeight = 1.0f / cardWidth;
    return {
        {"sphere light", sphereAreaLight(center, radius, white, kLumens), false},
        {"disk light", diskAreaLight(center, normal, radius, white, kLumens), false},
        {"rectangle light", rectangleAreaLight(center, normal, tangent, 1.0f, 1.0f, white, kLumens), false},
        {"textured card", rectangleAreaLight(center, normal, tangent, cardWidth, cardHeight, white, kLumens),
         true}};
}

std::vector<AreaLightResult> shadeRuntime(const PreviewLight& l, const LightCardData& card,
                                          const std::vector<ShadingPoint>& points, const Executor& executor) {
    if (l.textured)
        return executor.usesOpenCL() ? shadeTexturedLightOpenCL(executor.cl(), l.light, card, points)
                                     : shadeTexturedLightCpu(l.light, card, points);
    return executor.usesOpenCL() ? shadeAreaLightOpenCL(executor.cl(), l.light, points)
                                 : shadeAreaLightCpu(l.light, points);
}

} // namespace

ImageRGBA lightCardEmission(const LightCardData& card) {
    const int width = int(card.layout.width), height = int(card.layout.height);
    ImageRGBA image(width, height);
    const std::uint32_t base = lightCardOffset(card.layout, 0, 0);
    for (std::size_t i = 0; i < image.pixels.size(); ++i)
        image.pixels[i] = glm::vec4(card.texels[base + 4 * i], card.texels[base + 4 * i + 1],
                                    card.texels[base + 4 * i + 2], 1.0f);
    return image;
}

ImageRGBA previewCardEmission() {
    const int size = 64;
    ImageRGBA image(size, size);
    double sum = 0.0;
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
            const float u = (float(x) + 0.5f) / float(size), v = (float(y) + 0.5f) / float(size);
            const bool frame = std::abs(u - 0.5f) < 0.06f || std::abs(v - 0.5f) < 0.06f || u < 0.06f ||
                               u > 0.94f || v < 0.06f || v > 0.94f;
            const float t = 0.5f * (u + v);
            const glm::vec3 pane = glm::mix(glm::vec3(1.0f, 0.75f, 0.45f), glm::vec3(0.45f, 0.65f, 1.0f), t);
            const glm::vec3 c = frame ? glm::vec3(0.03f) : pane;
            image.at(x, y) = glm::vec4(c, 1.0f);
            sum += rec709Luminance(c);
        }
    const float scale = float(double(size * size) / sum);
    for (glm::vec4& p : image.pixels)
        p = glm::vec4(glm::vec3(p) * scale, 1.0f);
    return image;
}

LightPreview renderLightPreview(const LightCardData& card, const ImageRGBA& emission,
                                const Executor& executor, const LightPreviewSettings& settings,
                                const std::filesystem::path& png, const std::filesystem::path& exr) {
    const int size = settings.sphereSize;
    const std::vector<PreviewLight> lights = previewLights(settings.distance, card.layout.aspect);
    const int rows = int(lights.size());
    std::vector<int> owner;
    // One ball per (light, roughness); the shading points of each light are that row's balls.
    const std::vector<ShadingPoint> points =
        previewBallPoints(size, kColumns, rows, owner, [](ShadingPoint& p, int, int column) {
            p.position = p.normal;
            p.baseColor = glm::vec3(0.8f);
            p.metallic = 0.0f;
            p.perceptualRoughness = float(column + 1) / float(kColumns);
        });
    std::vector<int> row(points.size());
    const int width = kColumns * size, height = rows * size;
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x)
            if (int k = owner[std::size_t(y) * width + x]; k >= 0) row[std::size_t(k)] = y / size;

    std::vector<glm::vec3> shaded(points.size()), reference(points.size()), check(points.size());
    for (int r = 0; r < rows; ++r) {
        std::vector<ShadingPoint> mine;
        std::vector<std::size_t> index;
        for (std::size_t k = 0; k < points.size(); ++k)
            if (row[k] == r) mine.push_back(points[k]), index.push_back(k);
        const PreviewLight& l = lights[std::size_t(r)];
        const std::vector<AreaLightResult> runtime = shadeRuntime(l, card, mine, executor);
        const std::vector<AreaReference> brute =
            l.textured ? renderTexturedLightReference(l.light, emission, mine, {}, settings.reference)
                       : renderAreaLightReference(l.light, mine, {}, settings.reference);
        for (std::size_t i = 0; i < mine.size(); ++i) {
            shaded[index[i]] = runtime[i].diffuse + runtime[i].specular;
            reference[index[i]] = glm::vec3(brute[i].value.total());
            check[index[i]] = glm::vec3(brute[i].diffuseError + brute[i].specularError);
        }
    }

    double sumLuminance = 0.0;
    for (const glm::vec3& c : shaded)
        sumLuminance += rec709Luminance(c);
    const float scale =
        float(0.18 * double(points.size()) / std::max(sumLuminance, 1e-12)) * std::exp2(settings.exposureEV);
    ImageRGBA image(3 * width, height);
    std::vector<glm::vec3> errorColor(points.size(), glm::vec3(0.0f));
    std::vector<std::vector<double>> error(std::size_t(rows), std::vector<double>(kColumns, 0.0));
    std::vector<std::vector<double>> sum = error, own = error;
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const int k = owner[std::size_t(y) * width + x];
            if (k < 0) continue;
            const glm::vec3 c = shaded[std::size_t(k)], r = reference[std::size_t(k)];
            const float difference = std::abs(rec709Luminance(c) - rec709Luminance(r));
            errorColor[std::size_t(k)] = previewErrorColor(difference / std::max(rec709Luminance(r), 1e-12f));
            image.at(x, y) = glm::vec4(c, 1.0f);
            image.at(width + x, y) = glm::vec4(r, 1.0f);
            image.at(2 * width + x, y) = glm::vec4(errorColor[std::size_t(k)] / scale, 1.0f);
            const std::size_t g = std::size_t(y / size), column = std::size_t(x / size);
            error[g][column] += difference;
            sum[g][column] += rec709Luminance(r);
            own[g][column] += rec709Luminance(check[std::size_t(k)]);
        }

    LightPreview out;
    PreviewGridLabels labels;
    for (int c = 0; c < kColumns; ++c)
        out.roughness.push_back(float(c + 1) / float(kColumns));
    for (std::size_t g = 0; g < std::size_t(rows); ++g) {
        out.lights.push_back(lights[g].name);
        for (int c = 0; c < kColumns; ++c) {
            error[g][std::size_t(c)] /= std::max(sum[g][std::size_t(c)], 1e-30);
            own[g][std::size_t(c)] /= std::max(sum[g][std::size_t(c)], 1e-30);
        }
    }
    out.error = error;
    out.referenceError = own;
    labels.roughness = out.roughness;
    labels.groups = out.lights;
    labels.error = error;
    labels.referenceError = own;
    labels.caption =
        "perceptual roughness; 1000 lm lights 2 light sizes from the ball, runtime vs fp64 brute force";
    const PreviewLayout layout = previewLayout(size, true, rows, kColumns);
    writePreviewGrid(png, layout, image, errorColor, owner, scale, labels);
    out.width = layout.width;
    out.height = layout.height;

    ExrOutputOptions exrOptions;
    exrOptions.channels = 3;
    exrOptions.attributes = {{"iblbake:preview", "lights: runtime | reference | error heat map"}};
    writeExr(exr, image, exrOptions);
    return out;
}

LightPreview renderLightPreviewFile(const std::filesystem::path& cardFile, const Executor& executor,
                                    const LightPreviewSettings& settings, const std::filesystem::path& png,
                                    const std::filesystem::path& exr) {
    if (png.extension() != ".png") throw Error(png.string() + ": the preview is written as .png");
    if (!cardFile.empty()) {
        const LightCardData card = loadLightCard(cardFile);
        return renderLightPreview(card, lightCardEmission(card), executor, settings, png, exr);
    }
    const ImageRGBA emission = previewCardEmission();
    LightCardSettings cardSettings;
    cardSettings.size = emission.width;
    const LightCard baked = bakeLightCard(emission, 1.0f, cardSettings, executor);
    return renderLightPreview(lightCardData(baked.layout, baked.levels), emission, executor, settings, png,
                              exr);
}

std::string lightPreviewErrorText(const LightPreview& preview) {
    std::string text =
        "error   relative mean per roughness column (luminance), the brute force's own in ()\n";
    for (std::size_t g = 0; g < preview.lights.size(); ++g) {
        text += formatText("  %-16s", preview.lights[g].c_str());
        for (std::size_t c = 0; c < preview.roughness.size(); ++c)
            text += formatText(" %.1f%% (%.2f%%)", 100.0 * preview.error[g][c],
                               100.0 * preview.referenceError[g][c]);
        text += "\n";
    }
    return text;
}

} // namespace ibl
