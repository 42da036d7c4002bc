// How the program's heap hands memory back: rarely. A render allocates and
// frees large arrays in waves (the OBJ parse's arrays, then the BVH build's,
// then the images); glibc's defaults give blocks of 128 KiB and more their own
// mappings, returned to the system when freed, and trim the heap's free top
// beyond 128 KiB, so each wave faults in fresh pages (the kernel clears each
// one; about 2 microseconds a 4 KiB page on the machines measured). Kept, the
// next wave reuses them. Measured (docs/performance.md): the 1M-triangle torus's
// load and prepare on one thread 67.9k -> 52.4k page faults, 0.76 -> 0.73 s.
#pragma once

namespace rayform::cli {

// Blocks below 32 MiB (glibc's own ceiling for its adaptive threshold) come
// from the heap, and up to 256 MiB of free heap is kept for reuse. Larger
// blocks still get mappings of their own, returned when freed. Call once,
// first thing in main; a no-op where the C library is not glibc.
void keep_freed_heap_for_reuse();

}  // namespace rayform::cli
