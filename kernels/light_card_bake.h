// The light card's bake (kernels/light_card.h): one work-item per texel of a specular level or a diffuse
// layer, the normalized integral sum T w / sum w of the source texture over the whole light with the card's
// kernel w, at the texel's centre. The source is a box-filtered level of the texture, fine enough that
// its texels are at most a quarter of the kernel's width beta (LightCardBakeParams.sourceWidth/Height);
// the sum over its texel centres is a midpoint rule on the light.
#ifndef IBL_LIGHT_CARD_BAKE_H
#define IBL_LIGHT_CARD_BAKE_H

#include "light_card.h"
#include "work_item.h"

IBL_BEGIN_NAMESPACE

// The kernel's argument by value (4-byte members only: the same layout in C++ and OpenCL C).
IBL_STRUCT(LightCardBakeParams) {
    uint32_t width, height;             // the output level or layer
    uint32_t sourceWidth, sourceHeight; // the source level
    float invBetaSqr;                   // 1 / beta^2, card units
    float sizeU, sizeV;                 // the light's width and height in card units: sqrt(aspect), 1 / that
    uint32_t pad;
};

IBL_FN void lightCardBakeItem(WorkItem t, IBL_GLOBAL float* out, LightCardBakeParams p,
                              IBL_GLOBAL const float* source) {
    float x = (IBL_FLOAT(t.x) + 0.5f) / IBL_FLOAT(p.width) * p.sizeU;
    float y = (IBL_FLOAT(t.y) + 0.5f) / IBL_FLOAT(p.height) * p.sizeV;
    float du = p.sizeU / IBL_FLOAT(p.sourceWidth), dv = p.sizeV / IBL_FLOAT(p.sourceHeight);
    float r = 0.0f, g = 0.0f, b = 0.0f, weightSum = 0.0f;
    for (uint j = 0u; j < p.sourceHeight; ++j) {
        float dy = (IBL_FLOAT(j) + 0.5f) * dv - y;
        float dy2 = dy * dy;
        IBL_UNIFORM_LOOP_HEAD();
        for (uint i = 0u; i < p.sourceWidth; ++i) {
            float dx = (IBL_FLOAT(i) + 0.5f) * du - x;
            float w = lightCardWeight(dx * dx + dy2, p.invBetaSqr);
            uint k = 4u * (j * p.sourceWidth + i);
            r += w * source[k];
            g += w * source[k + 1u];
            b += w * source[k + 2u];
            weightSum += w;
        }
    }
    float inv = 1.0f / weightSum;
    storeTexel(out, t, v3(r * inv, g * inv, b * inv));
}

IBL_END_NAMESPACE

#endif
