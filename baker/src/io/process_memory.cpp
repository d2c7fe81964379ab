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
    // And freed memory at the top of the heap is kept up to 64 MB, not given back past 128 KB (the default,
    // which the threshold set above also freezes): a block freed last is at the top, and the next item of a
    // batch faulted it in again page by page. `iblbake batch` of the seven shared HDRIs: 204,000 -> 10,600
    // page faults, 16.8-20.3 -> 13.9-14.9 s, the same peak memory (53 MB).
    mallopt(M_TRIM_THRESHOLD, 64 * 1024 * 1024);
#endif
}

} // namespace ibl
