// The CPU backend's LD items (ld.h's ldLevelItem, ldBrightItem and ldOnePassItem), compiled once for each
// instruction set in ld_host_items.cpp and chosen at load time.
#ifndef IBLBAKE_STAGES_LD_HOST_ITEMS_H
#define IBLBAKE_STAGES_LD_HOST_ITEMS_H

#include <ld.h>

namespace ibl {

void ldLevelItemHost(WorkItem t, float* out, LdParams params, const float* pyramid, const float* table);
void ldBrightItemHost(WorkItem t, float* out, LdParams params, const float* clusters, const float* bright,
                      const float* brightLanes);
void ldOnePassItemHost(WorkItem t, float* out, LdParams params, const float* pyramid, const float* table,
                       const float* clusters, const float* bright, const float* brightLanes);

} // namespace ibl

#endif
