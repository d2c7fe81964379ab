// Allocator policy for a baking process.
#pragma once

namespace ibl {

// Blocks up to 32 MB (a 1k lat-long, a 256-px cube, the statistics' tables) taken from the heap instead of
// each from its own mapping (glibc's M_MMAP_THRESHOLD; elsewhere a no-op). A bake allocates such blocks one
// after another; from its own mapping, a freed block goes back to the kernel and the next one is faulted in
// again page by page, a fault per 4 KB that costs 3-13 us on the 2-core VM the benchmarks ran on, while a
// freed heap block is reused; freed memory at the top of the heap is kept (up to 64 MB) rather than given
// back. `iblbake diffuse` of the 1k sample: 5,430 -> 4,400 page faults. Call it first in main() (the
// benchmarks' too, so that they measure the same policy), before the blocks it should apply to. The other
// half of the policy, transparent huge pages for the heap, is glibc's start-up tunable, which the front end
// sets for the engine (cli/front_end.cpp).
void reuseFreedBlocks();

} // namespace ibl
