// The light preview (`iblbake preview --lights`, issue 15 item 5): balls of perceptual roughness 0.1 ... 1
// (columns), a white-ish dielectric, each row lit by one area light (runtime_area_lights.h: sphere, disk,
// rectangle) or by a textured rectangle light (runtime_light_card.h) of the same power, placed the same
// way beside every ball; runtime | fp64 brute force | relative error, as the material preview's labelled
// grid (material_preview.h), and the linear panels as OpenEXR.
#pragma once

#include "iblbake/opencl/executor.h"
#include "iblbake/runtime/runtime_light_card.h"

#include <filesystem>
#include <string>
#include <vector>

namespace ibl {

struct LightPreviewSettings {
    int sphereSize = 48;     // pixels per ball
    float exposureEV = 0.0f; // exposure compensation in stops
    // The lights' centre from each ball's centre (unit ball), in light sizes (sqrt of the light's area):
    // 2 light sizes from the nearest point of the ball.
    float distance = 3.0f;
    // The brute force's grid (runtime_area_lights.h): coarser than its defaults, which converge far below
    // the preview's error colours; its own error estimate is printed beside the error.
    AreaReferenceSettings reference{32, 128, 4.0, 1e-4};
};

struct LightPreview {
    std::vector<std::string> lights; // per row group, top to bottom
    std::vector<float> roughness;    // per column
    // Relative mean luminance error per light and column, sum |runtime - reference| / sum reference over the
    // ball's pixels (diffuse + specular), and the reference's own estimate of its error on the same scale.
    std::vector<std::vector<double>> error, referenceError;
    int width = 0, height = 0; // of the PNG grid
};

// The emission of a card as its level 0, layer 0 holds it (normalized to mean luminance 1), for the brute
// force of the textured light.
ImageRGBA lightCardEmission(const LightCardData& card);

// A built-in card's emission for the preview without a card file: a window of four panes behind a dark
// cross (warm at the top left, cool at the bottom right), 64 x 64, mean luminance 1.
ImageRGBA previewCardEmission();

// Renders and writes `png` and `exr`. `card`: the textured light's card, `emission` its level-0 emission.
// Throws ibl::Error naming the file.
LightPreview renderLightPreview(const LightCardData& card, const ImageRGBA& emission,
                                const Executor& executor, const LightPreviewSettings& settings,
                                const std::filesystem::path& png, const std::filesystem::path& exr);

// The flow of `iblbake preview --lights [--card CARD.ktx2]`: the card from its file (loadLightCard), else
// previewCardEmission baked in-process (64 texels, 8 diffuse layers).
LightPreview renderLightPreviewFile(const std::filesystem::path& cardFile, const Executor& executor,
                                    const LightPreviewSettings& settings, const std::filesystem::path& png,
                                    const std::filesystem::path& exr);

// `iblbake preview --lights`' error lines: per light, the relative mean error per roughness column and the
// brute force's own.
std::string lightPreviewErrorText(const LightPreview& preview);

} // namespace ibl
