#include "heap_reuse.h"

#include <cstdlib>  // defines __GLIBC__ where the C library is glibc

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace rayform::cli {

void keep_freed_heap_for_reuse() {
#if defined(__GLIBC__)
  // Setting either turns glibc's adaptive thresholds off; both are advice (an
  // interposed allocator, such as a sanitizer's, may ignore them).
  (void)mallopt(M_MMAP_THRESHOLD, 32 << 20);
  (void)mallopt(M_TRIM_THRESHOLD, 256 << 20);
#endif
}

}  // namespace rayform::cli
