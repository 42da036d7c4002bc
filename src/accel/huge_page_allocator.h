// The allocator of the arrays that traversal reads at random (MeshAccel's
// nodes and packets): an array of at least huge_page_bytes is placed on whole
// 2 MiB pages and, on Linux, advised as transparent huge pages (madvise
// MADV_HUGEPAGE; the usual system setting "madvise" grants them only so).
// Incoherent rays on a large mesh touch a few lines of many pages each, more
// pages than 4 KiB TLB entries cover; Embree advises its BVH memory likewise
// (what random rays gain: docs/performance.md). On Linux such an array is a
// mapping of its own (mmap), returned with munmap. Smaller arrays, and systems
// without the advice, get ordinary aligned memory; the contents are the same
// either way.
#pragma once

#include <cstddef>
#include <cstdint>
#include <new>
#include <type_traits>
#include <utility>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace rayform {

inline constexpr size_t huge_page_bytes = size_t(2) << 20;

template <class T>
struct HugePageAllocator {
  using value_type = T;

  HugePageAllocator() = default;
  template <class U>
  HugePageAllocator(const HugePageAllocator<U>&) noexcept {}

  // resize() default-initialises (no zero fill of plain data): the builder
  // writes every byte of the nodes and packets itself, in parallel, and so
  // also first touches their pages in parallel.
  template <class U>
  void construct(U* p) noexcept(std::is_nothrow_default_constructible_v<U>) {
    ::new (static_cast<void*>(p)) U;
  }
  template <class U, class... Args>
  void construct(U* p, Args&&... args) {
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }

  T* allocate(size_t n) {
    if (n > max_size()) throw std::bad_array_new_length();
    const size_t bytes = n * sizeof(T);
    if (bytes < huge_page_bytes) return static_cast<T*>(::operator new(bytes, std::align_val_t(alignof(T))));
    const size_t whole = round_up(bytes);
#if defined(__linux__) && defined(MADV_HUGEPAGE)
    // A mapping of its own, not the heap's: fresh pages whose size the kernel
    // picks at their first touch, after the advice (memory malloc kept for
    // reuse may already sit on small pages). One huge page longer, then
    // trimmed to start on a huge page.
    void* m = ::mmap(nullptr, whole + huge_page_bytes, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
    if (m == MAP_FAILED) throw std::bad_alloc();
    const uintptr_t at = (reinterpret_cast<uintptr_t>(m) + huge_page_bytes - 1) & ~(huge_page_bytes - 1);
    const size_t head = at - reinterpret_cast<uintptr_t>(m);
    if (head > 0) ::munmap(m, head);
    if (head < huge_page_bytes) ::munmap(reinterpret_cast<void*>(at + whole), huge_page_bytes - head);
    // Only advice: where it is refused, the pages are small.
    (void)::madvise(reinterpret_cast<void*>(at), whole, MADV_HUGEPAGE);
    return reinterpret_cast<T*>(at);
#else
    return static_cast<T*>(::operator new(whole, std::align_val_t(huge_page_bytes)));
#endif
  }

  void deallocate(T* p, size_t n) noexcept {
    const size_t bytes = n * sizeof(T);
    // The unsized forms: clang (the fuzz build) declares the sized ones only with -fsized-deallocation.
    if (bytes < huge_page_bytes) ::operator delete(p, std::align_val_t(alignof(T)));
#if defined(__linux__) && defined(MADV_HUGEPAGE)
    else ::munmap(p, round_up(bytes));
#else
    else ::operator delete(p, std::align_val_t(huge_page_bytes));
#endif
  }

  // As std::allocator (PTRDIFF_MAX bytes): rounding up to whole pages, plus
  // the page of slack for the alignment, cannot overflow.
  static constexpr size_t max_size() noexcept { return size_t(-1) / 2 / sizeof(T); }

  template <class U>
  bool operator==(const HugePageAllocator<U>&) const noexcept {
    return true;
  }

 private:
  static size_t round_up(size_t bytes) { return (bytes + huge_page_bytes - 1) / huge_page_bytes * huge_page_bytes; }
};

}  // namespace rayform
