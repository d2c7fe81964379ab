// Allocator policy for a baking process.
#pragma once

namespace ibl {

// A bake allocates large blocks one after another (a 1k lat-long 8 MB, a 256-px cube 6 MB, tables), and
// memory the process touches for the first time costs a page fault per 4 KB page: 3-13 us each on the
// 2-core VM the benchmarks ran on (a 64 MB memset: 220 ms the first time, 2.3 ms the second), more than the
// arithmetic of a small job. With glibc (elsewhere a no-op) this
// - takes blocks up to 32 MB from the heap instead of each from its own mapping (M_MMAP_THRESHOLD): a freed
//   one is reused by the next instead of going back to the kernel to be faulted in again; larger blocks
//   (a 4k lat-long) keep their own mappings;
// - extends the heap once by 64 MB of address space marked for transparent huge pages (madvise
//   MADV_HUGEPAGE; physical memory is still taken only as it is touched, 2 MB at a time): a block in it
//   costs a fault per 2 MB instead of per 4 KB, and freed memory up to 64 MB is kept (M_TRIM_THRESHOLD).
//   Where the kernel has no huge page at hand (or THP is off) it falls back to 4 KB pages; with THP
//   "defrag" set to madvise it may first compact memory, which can stall on a fragmented machine.
// `iblbake-engine diffuse` of the 1k sample at 256 px: 7,890 page faults before the ingest work of
// issue 18, 4,400 with the first point, ~1,100-1,500 with both. Call it first in main().
void prepareBakeHeap();

} // namespace ibl
