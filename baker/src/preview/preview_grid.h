// The material preview's labelled PNG grid (material_preview.h PreviewLayout): the balls, row names,
// roughness labels, per-column errors and the error colour scale.
#pragma once

#include "iblbake/baker/material_preview.h"

namespace ibl {

// `panels`: the linear runtime | reference panels of renderMaterialPreview (kPreviewColumns x 2 balls of
// layout.sphereSize each); `errorColor[k]`: the display-referred error colour of shading point k;
// `owner`: the point of each panel pixel (-1 off the balls); `scale`: the tone scale.
void writePreviewGrid(const std::filesystem::path& png, const PreviewLayout& layout, const ImageRGBA& panels,
                      const std::vector<glm::vec3>& errorColor, const std::vector<int>& owner, float scale,
                      const MaterialPreview& preview);

} // namespace ibl
