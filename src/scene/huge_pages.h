// Transparent huge pages (2 MiB on x86-64) for large arrays. A random walk
// through a BVH of tens of MiB misses the TLB at almost every node with 4 KiB
// pages, and filling a fresh array of N MiB takes N * 256 page faults; with
// huge pages both shrink about 500-fold. Linux gives them to memory that asks
// for them (madvise(MADV_HUGEPAGE)) when /sys/kernel/mm/transparent_hugepage/
// enabled is "madvise" or "always"; elsewhere asking does nothing.
#pragma once

#include <cstddef>
#include <vector>

namespace rayform {

// Blocks smaller than this gain little (at most one huge page fits inside).
inline constexpr size_t huge_page_min_bytes = size_t(4) << 20;

// Asks for huge pages for the whole 2 MiB-aligned pages inside [data, data +
// bytes), when bytes >= huge_page_min_bytes. Only pages not yet touched get
// them: call it before the memory is first written. Failures are ignored
// (a kernel without transparent huge pages keeps 4 KiB pages).
void advise_huge_pages(void* data, size_t bytes);

// v.resize(n), an empty v's new storage in huge pages (advise_huge_pages
// between allocating it and filling it).
template <class T>
void resize_in_huge_pages(std::vector<T>& v, size_t n) {
  if (v.empty() && v.capacity() < n) {
    v.reserve(n);
    advise_huge_pages(v.data(), n * sizeof(T));
  }
  v.resize(n);
}

}  // namespace rayform
