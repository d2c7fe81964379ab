#include "ld_host_items.h"

#include "host_clones.h"

namespace ibl {

// The LD items run their sample and patch loops in float8 lanes (kernels/lanes.h, vector8.h on the host),
// compiled here for each of these instruction sets and chosen at load time: AVX-512 and AVX2 run a lane
// vector as one instruction, the portable x86-64 build as two SSE ones. Built without errno for sqrt and
// without FMA contraction (baker/CMakeLists.txt), so every clone computes the same bits.

IBL_HOST_CLONES void ldLevelItemHost(WorkItem t, float* out, LdParams params, const float* pyramid,
                                     const float* table) {
    ldLevelItem(t, out, params, pyramid, table);
}

IBL_HOST_CLONES void ldBrightItemHost(WorkItem t, float* out, LdParams params, const float* clusters,
                                      const float* bright, const float* brightLanes) {
    ldBrightItem(t, out, params, clusters, bright, brightLanes);
}

IBL_HOST_CLONES void ldOnePassItemHost(WorkItem t, float* out, LdParams params, const float* pyramid,
                                       const float* table, const float* clusters, const float* bright,
                                       const float* brightLanes) {
    ldOnePassItem(t, out, params, pyramid, table, clusters, bright, brightLanes);
}

} // namespace ibl
