// The rayform program's global operator new: malloc, as the default one, and
// for blocks of 4 MiB or more, transparent huge pages (2 MiB) asked for with
// madvise(MADV_HUGEPAGE) before the block is first written. A large OBJ's
// load and prepare fill hundreds of MiB of fresh arrays (the parser's, the
// joined ones, the mesh's, the BVH builder's); with 4 KiB pages that is one
// page fault per 4 KiB (the 1M-triangle torus: 78 000 faults, 19 000 with
// this). Linux grants the advice when /sys/kernel/mm/transparent_hugepage/
// enabled is "madvise" or "always"; elsewhere it does nothing. Only the
// whole 2 MiB pages inside a block are advised. The default operator delete
// (free) matches it; libstdc++'s array and nothrow forms call this one. The
// library's BVH arrays have their own allocator (accel/huge_page_allocator.h).
// Not in sanitizer builds, whose runtimes replace operator new themselves (to
// check new/delete pairs), nor in the library: a program chooses this.
#if defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(memory_sanitizer) || __has_feature(thread_sanitizer)
#define RAYFORM_SANITIZED 1
#endif
#endif
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
#define RAYFORM_SANITIZED 1
#endif

#ifndef RAYFORM_SANITIZED
#include <cstdint>
#include <cstdlib>
#include <new>
#include <sys/mman.h>

namespace {

constexpr std::size_t advised_min_bytes = std::size_t(4) << 20;

void advise_huge_pages(void* block, std::size_t bytes) {
#ifdef MADV_HUGEPAGE
  constexpr std::uintptr_t huge = std::uintptr_t(2) << 20;
  const std::uintptr_t begin = (reinterpret_cast<std::uintptr_t>(block) + huge - 1) & ~(huge - 1);
  const std::uintptr_t end = (reinterpret_cast<std::uintptr_t>(block) + bytes) & ~(huge - 1);
  if (end > begin) (void)madvise(reinterpret_cast<void*>(begin), end - begin, MADV_HUGEPAGE);
#else
  (void)block;
  (void)bytes;
#endif
}

}  // namespace

void* operator new(std::size_t bytes) {
  if (bytes == 0) bytes = 1;
  for (;;) {
    if (void* p = std::malloc(bytes)) {
      if (bytes >= advised_min_bytes) advise_huge_pages(p, bytes);
      return p;
    }
    const std::new_handler handler = std::get_new_handler();
    if (!handler) throw std::bad_alloc();
    handler();
  }
}
#endif
