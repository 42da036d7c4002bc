// The indices a predicate keeps, numbered in index order, by parallel tasks:
// each block of indices counts its kept ones, the counts' prefix sums give
// each block its first number, then each block numbers its own in order.
// The same numbers one loop over the indices would give.
#pragma once

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cstddef>
#include <vector>

namespace rayform {

// For the i in [0, n) with keep(i) (called twice per index, from several
// threads at once): sized(total) once, before any emit; then emit(i, rank)
// with rank = the kept indices before i. Blocks of `block` indices.
template <class Keep, class Sized, class Emit>
void select_in_order(size_t n, size_t block, const Keep& keep, const Sized& sized, const Emit& emit) {
  block = std::max<size_t>(block, 1);
  const size_t blocks = (n + block - 1) / block;
  std::vector<size_t> first(blocks + 1, 0);  // per block: the rank of its first kept index, then the total
  tbb::parallel_for(size_t(0), blocks, [&](size_t b) {
    size_t count = 0;
    for (size_t i = b * block, e = std::min(n, i + block); i < e; ++i) count += keep(i) ? 1 : 0;
    first[b + 1] = count;
  });
  for (size_t b = 0; b < blocks; ++b) first[b + 1] += first[b];
  sized(first[blocks]);
  tbb::parallel_for(size_t(0), blocks, [&](size_t b) {
    size_t rank = first[b];
    for (size_t i = b * block, e = std::min(n, i + block); i < e; ++i)
      if (keep(i)) emit(i, rank++);
  });
}

}  // namespace rayform
