#include "rayform/base/populate_pages.h"

#include <tbb/parallel_for.h>

#include <cstdint>

#if defined(__linux__)
#include <sys/mman.h>
#include <unistd.h>
#endif

namespace rayform {

void populate_pages(void* data, size_t bytes) {
#if defined(__linux__) && defined(MADV_POPULATE_WRITE)
  constexpr size_t block = size_t(4) << 20;
  if (data == nullptr || bytes < block) return;
  const uintptr_t page = uintptr_t(sysconf(_SC_PAGESIZE));
  const uintptr_t begin = (reinterpret_cast<uintptr_t>(data) + page - 1) / page * page;
  const uintptr_t end = (reinterpret_cast<uintptr_t>(data) + bytes) / page * page;
  if (end <= begin) return;
  const size_t blocks = (end - begin + block - 1) / block;
  tbb::parallel_for(size_t(0), blocks, [&](size_t b) {
    const uintptr_t lo = begin + b * block, hi = lo + block < end ? lo + block : end;
    (void)::madvise(reinterpret_cast<void*>(lo), hi - lo, MADV_POPULATE_WRITE);
  });
#else
  (void)data;
  (void)bytes;
#endif
}

}  // namespace rayform
