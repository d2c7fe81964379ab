// Light-card bake: one work-item per texel of a specular level or diffuse layer; the work-item lives in
// light_card_bake.h, the mapping in light_card.h.
#include "light_card_bake.h"

__kernel void lightCardBake(__global float* out, LightCardBakeParams params, __global const float* source) {
    lightCardBakeItem(imageWorkItem(params.width, params.height), out, params, source);
}
