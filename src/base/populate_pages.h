// Making the pages of a freshly allocated array present before one thread
// fills it. A fresh page costs a fault at its first write (on a virtual
// machine also the host's: 0.5-2.5 ms per MiB measured here, docs/performance.md),
// and a serial fill (std::vector's resize, a serial copy) pays all of them on
// one thread; populate_pages pays them in parallel tasks instead.
#pragma once

#include <cstddef>
#include <vector>

namespace rayform {

// Makes the whole pages inside [data, data + bytes) present and writable, in
// parallel tasks of 4 MiB (Linux's madvise(MADV_POPULATE_WRITE), 5.14 and
// later). Contents are unchanged: present pages stay as they are, absent
// pages of anonymous memory read as zeros either way. Only a hint: does
// nothing below 4 MiB, on other systems or where the kernel refuses it.
void populate_pages(void* data, size_t bytes);

// v.resize(n) (a serial value-initialisation) after the pages of the
// elements it adds were made present in parallel (populate_pages).
template <class T, class Allocator>
void resize_on_present_pages(std::vector<T, Allocator>& v, size_t n) {
  if (n <= v.size()) return v.resize(n);
  if (v.capacity() < n) v.reserve(n);
  populate_pages(v.data() + v.size(), (n - v.size()) * sizeof(T));
  v.resize(n);
}

}  // namespace rayform
