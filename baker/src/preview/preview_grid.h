// The material preview's labelled PNG grid (material_preview.h PreviewLayout): the balls, row names,
// roughness labels, per-column errors and the error colour scale.
#pragma once

#include "iblbake/baker/material_preview.h"

#include <functional>

namespace ibl {

// One shading point per ball pixel (orthographic camera on +Z looking down -Z, +Y up; the ball of radius
// 0.9 of its cell; the unit sphere's normals, positions left at 0) of a panel of
// columns x rows balls of `size` pixels; `material` sets each point's material from its ball. Pixels off
// the balls are left out and marked in `owner` with -1.
std::vector<ShadingPoint>
previewBallPoints(int size, int columns, int rows, std::vector<int>& owner,
                  const std::function<void(ShadingPoint&, int row, int column)>& material);

// What the grid labels: the columns' roughness, the groups' names and, with a reference, each group's
// per-column error and the reference's own estimate of it.
struct PreviewGridLabels {
    std::vector<float> roughness;
    std::vector<std::string> groups;
    std::vector<std::vector<double>> error, referenceError; // [group][column]
    std::string caption = "perceptual roughness (GGX alpha = roughness^2)";
};

// `panels`: the linear runtime | reference panels (layout.columnCount x layout.groupCount balls of
// layout.sphereSize each); `errorColor[k]`: the display-referred error colour of shading point k;
// `owner`: the point of each panel pixel (-1 off the balls); `scale`: the tone scale.
void writePreviewGrid(const std::filesystem::path& png, const PreviewLayout& layout, const ImageRGBA& panels,
                      const std::vector<glm::vec3>& errorColor, const std::vector<int>& owner, float scale,
                      const PreviewGridLabels& labels);

} // namespace ibl
