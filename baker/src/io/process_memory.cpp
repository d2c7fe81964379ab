// Allocator policy for a baking process (iblbake/baker/process_memory.h).
#include "iblbake/baker/process_memory.h"

#include <cstdlib> // defines __GLIBC__ on glibc (through <features.h>)

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace ibl {

void reuseFreedBlocks() {
#if defined(__GLIBC__)
    // 32 MB is the largest threshold glibc takes (DEFAULT_MMAP_THRESHOLD_MAX on 64-bit): larger blocks, e.g.
    // a 4k lat-long, keep their own mappings and go back to the kernel when freed. Setting it also turns off
    // glibc's own raising of the threshold, which only starts after the first such block is freed.
    mallopt(M_MMAP_THRESHOLD, 32 * 1024 * 1024);
#endif
}

} // namespace ibl
