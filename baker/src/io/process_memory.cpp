// Allocator policy for a baking process (iblbake/baker/process_memory.h).
#include "iblbake/baker/process_memory.h"

#include <cstdint>
#include <cstdlib> // defines __GLIBC__ on glibc (through <features.h>)

#if defined(__GLIBC__)
#include <malloc.h>
#include <sys/mman.h>
#include <unistd.h>
#endif

namespace ibl {

void prepareBakeHeap() {
#if defined(__GLIBC__)
    constexpr std::size_t kMiB = 1024 * 1024;
    constexpr std::size_t kHugePage = 2 * kMiB, kHugeHeap = 64 * kMiB;
    // 32 MB is the largest threshold glibc takes (DEFAULT_MMAP_THRESHOLD_MAX on 64-bit). Setting it also
    // turns off glibc's own raising of the threshold, which only starts once such a block has been freed.
    mallopt(M_MMAP_THRESHOLD, int(32 * kMiB));
    mallopt(M_TRIM_THRESHOLD, int(kHugeHeap));
    // A block the heap cannot hold makes glibc extend it by the block plus M_TOP_PAD; the extension, from
    // the block to the new end of the heap, is then marked, and the block freed back into it.
    mallopt(M_TOP_PAD, int(kHugeHeap));
    if (void* block = std::malloc(kHugePage)) {
        const std::uintptr_t first =
            (reinterpret_cast<std::uintptr_t>(block) + kHugePage - 1) & ~(kHugePage - 1);
        const std::uintptr_t end = reinterpret_cast<std::uintptr_t>(sbrk(0)) & ~(kHugePage - 1);
        if (end > first) madvise(reinterpret_cast<void*>(first), end - first, MADV_HUGEPAGE);
        std::free(block);
    }
    mallopt(M_TOP_PAD, int(128 * 1024)); // glibc's default again (DEFAULT_TOP_PAD)
#endif
}

} // namespace ibl
