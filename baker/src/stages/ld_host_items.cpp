#include "ld_host_items.h"

namespace ibl {

// The LD items run their sample and patch loops in float8 lanes (kernels/lanes.h, vector8.h on the host),
// compiled here for each of these instruction sets and chosen at load time: AVX-512 and AVX2 run a lane
// vector as one instruction, the portable x86-64 build as two SSE ones. Built without errno for sqrt and
// without FMA contraction (baker/CMakeLists.txt), so every clone computes the same bits. GCC only: clang
// refuses multiversioning with flatten, and builds with clang (the sanitizer build) need no speed here.
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
#define IBL_HOST_ITEM __attribute__((flatten, target_clones("avx512f", "avx2", "default")))
#else
#define IBL_HOST_ITEM
#endif

IBL_HOST_ITEM void ldLevelItemHost(WorkItem t, float* out, LdParams params, const float* pyramid,
                                   const float* table) {
    ldLevelItem(t, out, params, pyramid, table);
}

IBL_HOST_ITEM void ldBrightItemHost(WorkItem t, float* out, LdParams params, const float* clusters,
                                    const float* bright) {
    ldBrightItem(t, out, params, clusters, bright);
}

IBL_HOST_ITEM void ldOnePassItemHost(WorkItem t, float* out, LdParams params, const float* pyramid,
                                     const float* table, const float* clusters, const float* bright) {
    ldOnePassItem(t, out, params, pyramid, table, clusters, bright);
}

} // namespace ibl
