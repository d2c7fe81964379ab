// A kernel that checks the dispatch helper itself (tests/test_dispatch.cpp): every element is stored
// with its own coordinates, then an add pass adds an input to it, so a padding item that wrote, an
// element written twice or one left out shows in the output, on either backend.
#ifndef IBL_DISPATCH_CHECK_H
#define IBL_DISPATCH_CHECK_H

#include "work_item.h"

IBL_BEGIN_NAMESPACE

typedef struct {
    uint32_t width;  // cube face size, image width or list length
    uint32_t height; // image height (1 otherwise)
} DispatchCheckParams;

IBL_FN void dispatchCheckStoreItem(WorkItem t, IBL_GLOBAL float* out, DispatchCheckParams params) {
    storeTexelAlpha(out, t, v3((float)t.x, (float)t.y, (float)t.face), (float)t.offset);
}

IBL_FN void dispatchCheckAddItem(WorkItem t, IBL_GLOBAL float* out, DispatchCheckParams params,
                                 IBL_GLOBAL const float* increments) {
    addToTexel(out, t, loadTexel(increments, t));
}

IBL_END_NAMESPACE

#endif
