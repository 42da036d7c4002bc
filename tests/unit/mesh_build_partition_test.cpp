// The mesh BVH builder's split and partition (src/accel/mesh_build_split.h)
// by parallel tasks give exactly what one task gives: the same PrimRef array
// after each partition and the same boxes of both sides, bit for bit (+0 and
// -0 included), down several levels, for primitives on a coarse grid (many
// ties, signed zeros) and for a random soup. And the split find_split picks
// is the binned SAH's best, recomputed from the primitives themselves (large
// ranges bin into two sets of bins, merged; small ones into one).
#include "rayform/accel/mesh_build_split.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>
#include <tbb/task_arena.h>

#include <cstring>
#include <random>
#include <string>
#include <utility>
#include <vector>

namespace rayform::mesh_build {
namespace {

bool same_box(const Box& a, const Box& b) {
  float x[8], y[8];
  simd::store(x, a.lo);
  simd::store(x + 4, a.hi);
  simd::store(y, b.lo);
  simd::store(y + 4, b.hi);
  // Lane 3 is not part of the box.
  return std::memcmp(x, y, 3 * sizeof(float)) == 0 && std::memcmp(x + 4, y + 4, 3 * sizeof(float)) == 0;
}

bool same_range(const Range& a, const Range& b) {
  return a.begin == b.begin && a.end == b.end && same_box(a.geom, b.geom) && same_box(a.cent, b.cent);
}

enum class Layout { soup, grid_positive, grid_negative };

// n primitives: a random soup, or boxes on a grid of quarter steps touching
// zero from above (grid_positive: the lowest bounds tie at +0 and -0) or from
// below (grid_negative: the highest do), where the order of accumulation
// decides which zero a box keeps.
std::vector<PrimRef> make_refs(uint32_t n, Layout layout, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(-1.f, 1.f);
  auto zero = [&] { return rng() & 1 ? 0.f : -0.f; };
  std::vector<PrimRef> refs(n);
  for (uint32_t i = 0; i < n; ++i) {
    PrimRef& p = refs[i];
    for (int a = 0; a < 3; ++a) {
      float lo, hi;
      if (layout == Layout::soup) {
        lo = u(rng);
        hi = lo + 0.1f * (u(rng) + 1.f);
      } else {
        const int k = int(rng() % 4), m = int(rng() % 3);
        lo = k == 0 ? zero() : 0.25f * float(k);
        hi = m == 0 ? lo : lo + 0.25f * float(m);
        if (layout == Layout::grid_negative) std::swap(lo, hi), lo = -lo, hi = -hi;
      }
      p.lo[a] = lo;
      p.hi[a] = hi;
    }
    p.lo[3] = std::bit_cast<float>(i);
    p.hi[3] = 1.f;
  }
  return refs;
}

Range root_of(const std::vector<PrimRef>& refs) {
  Range r;
  for (const PrimRef& p : refs) add(r, p);
  r.begin = 0;
  r.end = uint32_t(refs.size());
  return r;
}

// Splits and partitions r with both splitters, compares, and goes down both
// sides for `levels` more levels.
void split_both(RangeSplitter& one, std::vector<PrimRef>& one_refs, RangeSplitter& many,
                std::vector<PrimRef>& many_refs, const Range& r, int levels, const std::string& where) {
  if (r.count() < 2) return;
  const Split s1 = one.find_split(r, 0), s2 = many.find_split(r, 0);
  ASSERT_EQ(s1.axis, s2.axis) << where;
  ASSERT_EQ(s1.pos, s2.pos) << where;
  ASSERT_EQ(s1.left, s2.left) << where;
  ASSERT_EQ(std::memcmp(&s1.cost, &s2.cost, sizeof(float)), 0) << where;
  const auto [l1, r1] = one.partition(r, s1);
  const auto [l2, r2] = many.partition(r, s2);
  ASSERT_TRUE(same_range(l1, l2)) << where << ": left boxes differ";
  ASSERT_TRUE(same_range(r1, r2)) << where << ": right boxes differ";
  ASSERT_EQ(std::memcmp(one_refs.data() + r.begin, many_refs.data() + r.begin, r.count() * sizeof(PrimRef)), 0)
      << where << ": the arrays differ after the partition";
  if (levels == 0) return;
  split_both(one, one_refs, many, many_refs, l1, levels - 1, where + "L");
  split_both(one, one_refs, many, many_refs, r1, levels - 1, where + "R");
}

void expect_same_partitions(uint32_t n, Layout layout, int bins) {
  std::vector<PrimRef> one_refs = make_refs(n, layout, n), many_refs = one_refs;
  RangeSplitter one(one_refs, bins, 1.f, /*parallel_threshold*/ n + 1);
  RangeSplitter many(many_refs, bins, 1.f, /*parallel_threshold*/ 64);
  const Range root = root_of(one_refs);
  // Four workers even on a machine with fewer cores: the tasks interleave.
  tbb::global_control threads(tbb::global_control::max_allowed_parallelism, 4);
  tbb::task_arena arena(4);
  arena.execute([&] { split_both(one, one_refs, many, many_refs, root, 5, "root "); });
}

TEST(MeshBuildPartition, ParallelPartitionEqualsOneTaskOnAGridWithSignedZeros) {
  expect_same_partitions(200000, Layout::grid_positive, 16);
  expect_same_partitions(70001, Layout::grid_negative, 64);
}

TEST(MeshBuildPartition, ParallelPartitionEqualsOneTaskOnARandomSoup) {
  expect_same_partitions(150000, Layout::soup, 32);
  expect_same_partitions(1000, Layout::soup, 8);
}

// find_split(r) against the SAH of every candidate plane recomputed from the
// primitives and the bins find_split recorded in them: the same first best
// (axis, then plane, in order), the same count on the left, the same cost.
void expect_best_binned_split(uint32_t n, Layout layout, int bins) {
  std::vector<PrimRef> refs = make_refs(n, layout, n + 7);
  RangeSplitter splitter(refs, bins, 1.f, /*parallel_threshold*/ 1u << 30);
  const Range r = root_of(refs);
  const Split s = splitter.find_split(r, 0);
  ASSERT_GE(s.axis, 0);
  float best = infinity;
  int best_axis = -1, best_pos = -1;
  uint32_t best_left = 0;
  for (int a = 0; a < 3; ++a)
    for (int pos = 0; pos + 1 < s.nb; ++pos) {
      Box left, right;
      uint32_t nl = 0, nr = 0;
      for (const PrimRef& p : refs) {
        const f4 lo = simd::load(p.lo), hi = simd::load(p.hi);
        if (int(p.bin(a)) <= pos) left.expand(lo, hi), ++nl;
        else right.expand(lo, hi), ++nr;
      }
      if (nl == 0 || nr == 0) continue;
      const float cost = left.half_area() * float(blocks(nl)) + right.half_area() * float(blocks(nr));
      if (cost < best) best = cost, best_axis = a, best_pos = pos, best_left = nl;
    }
  EXPECT_EQ(s.axis, best_axis);
  EXPECT_EQ(s.pos, best_pos);
  EXPECT_EQ(s.left, best_left);
  EXPECT_EQ(s.cost, 1.f + best / r.geom.half_area());
}

TEST(MeshBuildSplit, FindSplitIsTheBestBinnedSahSplitOfItsPrimitives) {
  expect_best_binned_split(100, Layout::soup, 16);   // one set of bins
  expect_best_binned_split(5001, Layout::soup, 16);  // two sets, an odd count
  expect_best_binned_split(4096, Layout::grid_positive, 16);
  expect_best_binned_split(3001, Layout::grid_negative, 64);
}

}  // namespace
}  // namespace rayform::mesh_build
