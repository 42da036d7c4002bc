// How the program's heap hands memory back: rarely. A render allocates and
// frees large arrays in waves (the OBJ parse's arrays, then the BVH build's,
// then the images); glibc's defaults give blocks of 128 KiB and more their own
// mappings, returned to the system when freed, and trim the heap's free top
// beyond 128 KiB, so each wave would fault in fresh pages, each one cleared by
// the kernel at its first touch. Kept for reuse, the freed pages serve the
// next wave without those faults (docs/performance.md).
#pragma once

namespace rayform::cli {

// Blocks below 32 MiB (glibc's own ceiling for its adaptive threshold) come
// from the heap, and up to 256 MiB of free heap is kept for reuse. Larger
// blocks still get mappings of their own, returned when freed. Call once,
// first thing in main; a no-op where the C library is not glibc.
void keep_freed_heap_for_reuse();

}  // namespace rayform::cli
