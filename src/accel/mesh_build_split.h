// Where the MeshAccel builder (mesh_accel_builder.h) splits a range of
// primitives: the binned SAH over its doubled centroids (or by count, where
// no SAH split exists or the tree is deep), and the partition of the PrimRef
// array by it.
#pragma once

#include "rayform/accel/mesh_build_refs.h"

#include <tbb/blocked_range.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <utility>
#include <vector>

namespace rayform::mesh_build {

constexpr int max_bins = 64;
static_assert(max_bins <= PrimRef::bin_mask + 1);

struct Split {
  int axis = -1;                // -1: no SAH split (split by count)
  int nb = 0;                   // bins per axis
  int pos = 0;                  // primitives in bins <= pos go left
  uint32_t left = 0;            // how many primitives go left
  float cost = infinity;        // SAH cost relative to a packet test
  float lo = 0.f, scale = 0.f;  // bin = (c - lo) * scale on `axis`
};

// Per axis and bin: the box of the primitives whose centroid falls in it, and
// their count. Only the first `nb` bins of each axis are used (and cleared).
struct Bins {
  f4 lo[3][max_bins], hi[3][max_bins];
  uint32_t count[3][max_bins];
  void clear(int nb) {
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < nb; ++b) {
        lo[a][b] = simd::splat(infinity);
        hi[a][b] = simd::splat(-infinity);
        count[a][b] = 0;
      }
  }
  void merge(const Bins& o, int nb) {
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < nb; ++b) {
        lo[a][b] = simd::vmin(lo[a][b], o.lo[a][b]);
        hi[a][b] = simd::vmax(hi[a][b], o.hi[a][b]);
        count[a][b] += o.count[a][b];
      }
  }
};

// Finds splits of ranges of a PrimRef array and partitions the array by them.
class RangeSplitter {
 public:
  // bins_per_axis in [2, max_bins]; traversal_cost >= 0. Ranges of at least
  // parallel_threshold primitives are partitioned by parallel tasks (the same
  // array and boxes as one task gives; tests set a smaller threshold).
  RangeSplitter(std::vector<PrimRef>& refs, int bins_per_axis, float traversal_cost,
                uint32_t parallel_threshold = default_parallel_threshold)
      : refs_(refs),
        bins_per_axis_(bins_per_axis),
        traversal_cost_(traversal_cost),
        parallel_threshold_(std::max(parallel_threshold, 1u)) {}

  static constexpr uint32_t default_parallel_threshold = 1u << 15;

  // The best SAH split of r. Bins r's primitives, which partition(r, split)
  // then reads: nothing may reorder r in between.
  Split find_split(const Range& r, int depth) {
    Split best;
    if (depth > sah_depth_limit) return best;
    float clo[4], chi[4], scale[4] = {0.f, 0.f, 0.f, 0.f};
    simd::store(clo, r.cent.lo);
    simd::store(chi, r.cent.hi);
    // Fewer bins for few primitives (the sweep costs as much as the binning there).
    const int nb = std::min(bins_per_axis_, std::max(4, int(r.count() / 2)));
    bool any = false;
    for (int a = 0; a < 3; ++a) {
      float ext = chi[a] - clo[a];
      if (ext > 0.f && std::isfinite(ext)) {
        scale[a] = float(nb) * (1.f - 1e-6f) / ext;
        any = true;
      }
    }
    if (!any) return best;
    const f4 vlo = simd::loadu(clo), vscale = simd::loadu(scale);
    Bins bins;
    bins.clear(nb);
    if (r.count() >= parallel_threshold_) {
      bins = tbb::parallel_reduce(
          tbb::blocked_range<uint32_t>(r.begin, r.end, 1u << 13), bins,
          [&](const tbb::blocked_range<uint32_t>& br, Bins acc) {
            bin_range(br.begin(), br.end(), vlo, vscale, nb, acc);
            return acc;
          },
          [&](Bins a, const Bins& b) {
            a.merge(b, nb);
            return a;
          });
    } else {
      bin_range(r.begin, r.end, vlo, vscale, nb, bins);
    }
    for (int a = 0; a < 3; ++a) {
      if (scale[a] == 0.f) continue;
      float right_area[max_bins];
      uint32_t right_count[max_bins];
      Box acc;
      uint32_t n = 0;
      for (int i = nb - 1; i > 0; --i) {
        acc.expand(bins.lo[a][i], bins.hi[a][i]);
        n += bins.count[a][i];
        right_area[i] = acc.half_area();
        right_count[i] = n;
      }
      acc = Box{};
      n = 0;
      for (int i = 0; i < nb - 1; ++i) {
        acc.expand(bins.lo[a][i], bins.hi[a][i]);
        n += bins.count[a][i];
        if (n == 0 || right_count[i + 1] == 0) continue;
        float cost = acc.half_area() * float(blocks(n)) + right_area[i + 1] * float(blocks(right_count[i + 1]));
        if (cost < best.cost) {
          best.cost = cost;
          best.axis = a;
          best.nb = nb;
          best.pos = i;
          best.left = n;
          best.lo = clo[a];
          best.scale = scale[a];
        }
      }
    }
    if (best.axis >= 0) {
      float area = r.geom.half_area();
      best.cost = traversal_cost_ + (area > 0.f ? best.cost / area : 0.f);
    }
    return best;
  }

  // Splits r by s (or, without a SAH split, by count) into two non-empty ranges.
  std::pair<Range, Range> partition(const Range& r, const Split& s) {
    Range left, right;
    uint32_t mid = r.begin + s.left;
    if (s.axis >= 0 && mid != r.begin && mid != r.end) {
      // The boxes as Hoare's partition accumulates them: [begin, mid) upwards,
      // [mid, end) downwards (which only matters where +0 and -0 tie).
      // On one thread the serial scans are cheaper (one pass instead of three).
      if (r.count() >= parallel_threshold_ && several_threads()) {
        swap_misplaced_parallel(r, s);
        left = boxes_in_parallel(r.begin, mid, false);
        right = boxes_in_parallel(mid, r.end, true);
      } else {
        swap_misplaced(r, s);
        for (uint32_t i = r.begin; i < mid; ++i) add(left, refs_[i]);
        for (uint32_t i = mid; i < r.end; ++i) add_before(right, refs_[i]);
      }
    } else {
      // By count, at the median of the widest centroid axis when there is one.
      mid = r.begin + r.count() / 2;
      float clo[4], chi[4];
      simd::store(clo, r.cent.lo);
      simd::store(chi, r.cent.hi);
      int axis = 0;
      for (int a = 1; a < 3; ++a)
        if (chi[a] - clo[a] > chi[axis] - clo[axis]) axis = a;
      if (chi[axis] > clo[axis])
        std::nth_element(refs_.begin() + r.begin, refs_.begin() + mid, refs_.begin() + r.end,
                         [axis](const PrimRef& a, const PrimRef& b) {
                           float ca = a.lo[axis] + a.hi[axis], cb = b.lo[axis] + b.hi[axis];
                           return ca < cb || (ca == cb && a.id() < b.id());
                         });
      for (uint32_t i = r.begin; i < mid; ++i) add(left, refs_[i]);
      for (uint32_t i = mid; i < r.end; ++i) add(right, refs_[i]);
    }
    left.begin = r.begin;
    left.end = mid;
    right.begin = mid;
    right.end = r.end;
    return {left, right};
  }

 private:
  // Whether tasks may run on more than one thread (the arena's and the
  // process's bounds, base/thread_limit.h).
  static bool several_threads() {
    return tbb::this_task_arena::max_concurrency() > 1 &&
           tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism) > 1;
  }

  // Beyond this depth, splits by count (each child at most half) keep the
  // tree within sah_depth_limit + 33 levels, which bounds the traversal stack.
  static constexpr int sah_depth_limit = 32;

  std::vector<PrimRef>& refs_;
  int bins_per_axis_;
  float traversal_cost_;
  uint32_t parallel_threshold_;  // ranges at least this large are binned and partitioned by parallel tasks

  // Bins refs_[begin, end) by their doubled centroids, and records each one's
  // bins in it for partition.
  // Many primitives go to two sets of bins, alternately, merged at the end:
  // neighbours often share a bin, and one set would chain each one's update
  // of it to the previous one's. The boxes' areas and the counts are the same
  // (the minima and maxima only, possibly, a zero's sign), so the split is.
  void bin_range(uint32_t begin, uint32_t end, const f4& clo, const f4& scale, int nb, Bins& bins) {
    constexpr uint32_t two_sets_from = 256;
    if (end - begin < two_sets_from) {
      for (uint32_t i = begin; i < end; ++i) bin_one(refs_[i], clo, scale, nb, bins);
      return;
    }
    Bins odd;
    odd.clear(nb);
    uint32_t i = begin;
    for (; i + 1 < end; i += 2) {
      bin_one(refs_[i], clo, scale, nb, bins);
      bin_one(refs_[i + 1], clo, scale, nb, odd);
    }
    if (i < end) bin_one(refs_[i], clo, scale, nb, bins);
    bins.merge(odd, nb);
  }

  // Bins one primitive and records its bins in it.
  static void bin_one(PrimRef& p, const f4& clo, const f4& scale, int nb, Bins& bins) {
    f4 lo = simd::load(p.lo), hi = simd::load(p.hi);
    int b[4];
    simd::to_int_clamped((lo + hi - clo) * scale, nb - 1, b);
    p.hi[3] = PrimRef::bin_bits(uint32_t(b[0]), uint32_t(b[1]), uint32_t(b[2]));
    for (int a = 0; a < 3; ++a) {
      bins.lo[a][b[a]] = simd::vmin(bins.lo[a][b[a]], lo);
      bins.hi[a][b[a]] = simd::vmax(bins.hi[a][b[a]], hi);
      bins.count[a][b[a]]++;
    }
  }

  // Moves the primitives of r going left by s (bin <= s.pos, as find_split
  // recorded) to [begin, mid) and the others to [mid, end), mid = begin +
  // s.left, as Hoare's partition does: the k-th primitive going right in
  // [begin, mid) from the left swaps with the k-th going left in [mid, end)
  // from the right. Branch-free scans over blocks of positions.
  void swap_misplaced(const Range& r, const Split& s) {
    constexpr uint32_t block = 64;
    const uint32_t mid = r.begin + s.left, pos = uint32_t(s.pos);
    const int axis = s.axis;
    uint32_t lpos[block], rpos[block];  // positions of misplaced primitives, in pairing order
    uint32_t a = r.begin, b = r.end;    // next to scan: a upwards, b - 1 downwards
    uint32_t nl = 0, il = 0, nr = 0, ir = 0;
    for (;;) {
      if (il == nl) {
        il = nl = 0;
        for (const uint32_t stop = a + std::min(block, mid - a); a < stop; ++a) {
          lpos[nl] = a;
          nl += refs_[a].bin(axis) > pos;
        }
      }
      if (ir == nr) {
        ir = nr = 0;
        for (const uint32_t stop = b - std::min(block, b - mid); b > stop; --b) {
          rpos[nr] = b - 1;
          nr += refs_[b - 1].bin(axis) <= pos;
        }
      }
      const uint32_t k = std::min(nl - il, nr - ir);
      for (uint32_t t = 0; t < k; ++t) std::swap(refs_[lpos[il + t]], refs_[rpos[ir + t]]);
      il += k;
      ir += k;
      if ((il == nl && a == mid) || (ir == nr && b == mid)) break;
    }
  }

  // swap_misplaced by parallel tasks, with the same result: the k-th
  // misplaced primitive of [begin, mid) counted upwards swaps with the k-th
  // misplaced one of [mid, end) counted downwards. Blocks count their
  // misplaced primitives, then list their positions at their ranks, then the
  // pairs swap (disjoint, so in any order).
  [[gnu::noinline]] void swap_misplaced_parallel(const Range& r, const Split& s) {
    constexpr uint32_t block = 1u << 13;
    const uint32_t mid = r.begin + s.left, pos = uint32_t(s.pos);
    const int axis = s.axis;
    const uint32_t left_blocks = (mid - r.begin + block - 1) / block, right_blocks = (r.end - mid + block - 1) / block;
    // Block b < left_blocks: [r.begin + b block, ...) up to mid, scanned upwards;
    // block left_blocks + j: (..., r.end - j block) down to mid, scanned downwards.
    auto left_block = [&](uint32_t b) {
      return std::pair{r.begin + b * block, std::min(mid, r.begin + (b + 1) * block)};
    };
    auto right_block = [&](uint32_t j) {
      return std::pair{r.end - std::min(r.end - mid, (j + 1) * block), r.end - j * block};
    };
    auto misplaced_left = [&](uint32_t i) { return refs_[i].bin(axis) > pos; };
    auto misplaced_right = [&](uint32_t i) { return refs_[i].bin(axis) <= pos; };
    std::vector<uint32_t> first(left_blocks + right_blocks + 2, 0);  // per block: rank of its first misplaced one
    tbb::parallel_for(uint32_t(0), left_blocks + right_blocks, [&](uint32_t b) {
      uint32_t n = 0;
      if (b < left_blocks) {
        auto [lo, hi] = left_block(b);
        for (uint32_t i = lo; i < hi; ++i) n += misplaced_left(i);
      } else {
        auto [lo, hi] = right_block(b - left_blocks);
        for (uint32_t i = lo; i < hi; ++i) n += misplaced_right(i);
      }
      first[b + 1 + (b >= left_blocks)] = n;
    });
    // Exclusive sums: left blocks in first[0 .. left_blocks], right blocks
    // after a second zero at first[left_blocks + 1].
    for (uint32_t b = 0; b < left_blocks; ++b) first[b + 1] += first[b];
    for (uint32_t j = 0; j < right_blocks; ++j) first[left_blocks + 2 + j] += first[left_blocks + 1 + j];
    const uint32_t misplaced = first[left_blocks];
    if (first[left_blocks + 1 + right_blocks] != misplaced) return swap_misplaced(r, s);  // not a split of r
    std::vector<uint32_t> left_pos(misplaced), right_pos(misplaced);
    tbb::parallel_for(uint32_t(0), left_blocks + right_blocks, [&](uint32_t b) {
      if (b < left_blocks) {
        auto [lo, hi] = left_block(b);
        uint32_t k = first[b];
        for (uint32_t i = lo; i < hi; ++i)
          if (misplaced_left(i)) left_pos[k++] = i;
      } else {
        const uint32_t j = b - left_blocks;
        auto [lo, hi] = right_block(j);
        uint32_t k = first[left_blocks + 1 + j];
        for (uint32_t i = hi; i > lo; --i)
          if (misplaced_right(i - 1)) right_pos[k++] = i - 1;
      }
    });
    tbb::parallel_for(tbb::blocked_range<uint32_t>(0, misplaced, block), [&](const tbb::blocked_range<uint32_t>& br) {
      for (uint32_t k = br.begin(); k < br.end(); ++k) std::swap(refs_[left_pos[k]], refs_[right_pos[k]]);
    });
  }

  // The boxes of refs_[begin, end) by parallel tasks, equal to adding them
  // in order one by one (add, or add_before where `before`): where bounds tie
  // (+0 and -0), add keeps the last primitive's and add_before the first's.
  // Each block of the range is boxed by one task; the blocks' boxes are then
  // joined in order, which keeps the same one.
  [[gnu::noinline]] Range boxes_in_parallel(uint32_t begin, uint32_t end, bool before) const {
    constexpr uint32_t block = 1u << 13;
    const uint32_t blocks = (end - begin + block - 1) / block;
    std::vector<Range> parts(blocks);
    tbb::parallel_for(uint32_t(0), blocks, [&](uint32_t b) {
      const uint32_t lo = begin + b * block, hi = std::min(end, lo + block);
      Range& acc = parts[b];
      if (before)
        for (uint32_t i = lo; i < hi; ++i) add_before(acc, refs_[i]);
      else
        for (uint32_t i = lo; i < hi; ++i) add(acc, refs_[i]);
    });
    Range all;
    for (const Range& part : parts) {
      if (before) {
        all.geom.expand_before(part.geom.lo, part.geom.hi);
        all.cent.expand_before(part.cent.lo, part.cent.hi);
      } else {
        all.geom.expand(part.geom);
        all.cent.expand(part.cent);
      }
    }
    return all;
  }
};

}  // namespace rayform::mesh_build
