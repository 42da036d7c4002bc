// The rayform program's global operator new: malloc, as the default one, and
// for blocks of huge_page_min_bytes or more, transparent huge pages asked for
// before the block is first written (scene/huge_pages.h). A large OBJ's load
// and prepare fill hundreds of MiB of fresh arrays (the parser's, the joined
// ones, the mesh's, the BVH builder's); with 4 KiB pages that is one page
// fault per 4 KiB. The default operator delete (free) matches it; the array
// and nothrow forms of libstdc++ call this one. Not in sanitizer builds,
// whose runtimes replace operator new themselves (to check new/delete pairs),
// nor in the library: a program chooses its allocator.
#if defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(memory_sanitizer) || __has_feature(thread_sanitizer)
#define RAYFORM_SANITIZED 1
#endif
#endif
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
#define RAYFORM_SANITIZED 1
#endif

#ifndef RAYFORM_SANITIZED
#include "rayform/scene/huge_pages.h"

#include <cstdlib>
#include <new>

void* operator new(std::size_t bytes) {
  if (bytes == 0) bytes = 1;
  for (;;) {
    if (void* p = std::malloc(bytes)) {
      if (bytes >= rayform::huge_page_min_bytes) rayform::advise_huge_pages(p, bytes);
      return p;
    }
    const std::new_handler handler = std::get_new_handler();
    if (!handler) throw std::bad_alloc();
    handler();
  }
}
#endif
