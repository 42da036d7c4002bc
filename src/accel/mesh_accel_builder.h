// The internals of the MeshAccel builder (mesh_accel.h), shared by the whole
// build (mesh_accel_build.cpp) and the build shared among the parts of a
// WorkShare (mesh_accel_share.cpp): triangle boxes, then a binned SAH build
// of an 8-wide tree run in parallel with oneTBB, then the tree written depth
// first into WideBvhNodes and TrianglePackets. Deterministic: the same input
// gives the same structure whatever the number of threads (parallel tasks
// work on disjoint ranges, reductions merge in a fixed order, and the
// flattening offsets come from subtree totals). Private to those two files
// (not installed: it includes oneTBB).
#pragma once

#include "rayform/accel/mesh_accel.h"
#include "rayform/accel/simd4.h"

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <deque>
#include <optional>
#include <span>
#include <stdexcept>
#include <utility>
#include <vector>

namespace rayform::mesh_build {

using simd::f4;

// A triangle's box, 32 bytes: lanes 0..2 of lo/hi are the box, lane 3 of lo
// holds the triangle id (its bits), lane 3 of hi the bins of its last binning
// (see bin_bits).
struct alignas(16) PrimRef {
  float lo[4];
  float hi[4];
  uint32_t id() const { return std::bit_cast<uint32_t>(lo[3]); }
  // The bin on `axis` that find_split last gave this primitive.
  uint32_t bin(int axis) const { return (std::bit_cast<uint32_t>(hi[3]) >> (bin_shift * axis)) & bin_mask; }

  static constexpr int bin_shift = 6;  // bits per axis; bins < 64
  static constexpr uint32_t bin_mask = (1u << bin_shift) - 1;
  // hi[3] for bins b0, b1, b2: their bits under the exponent of 1.0f, so that
  // lane 3 stays a normal float (denormals can be slow in the box arithmetic).
  static float bin_bits(uint32_t b0, uint32_t b1, uint32_t b2) {
    return std::bit_cast<float>(0x3f800000u | b0 | b1 << bin_shift | b2 << (2 * bin_shift));
  }
};
static_assert(sizeof(PrimRef) == 32);

// Box in SIMD registers; lane 3 is ignored.
struct Box {
  f4 lo = simd::splat(infinity), hi = simd::splat(-infinity);
  void expand(f4 l, f4 h) {
    lo = simd::vmin(lo, l);
    hi = simd::vmax(hi, h);
  }
  void expand(const Box& b) { expand(b.lo, b.hi); }
  // As expand, but where bounds tie (+0 and -0) the box keeps its own: the
  // result of expanding by l, h before the items already in the box.
  void expand_before(f4 l, f4 h) {
    lo = simd::vmin(l, lo);
    hi = simd::vmax(h, hi);
  }
  // Half the surface area; 0 for an empty box.
  float half_area() const { return simd::half_area(lo, hi); }
};

// Items [begin, end) of the PrimRef array with their box and the box of their
// doubled centroids (lo + hi, which saves a multiply per primitive).
struct Range {
  uint32_t begin = 0, end = 0;
  Box geom, cent;
  uint32_t count() const { return end - begin; }
};

// Adds a primitive's box and doubled centroid to r's boxes (not to its items).
inline void add(Range& r, const PrimRef& p) {
  f4 lo = simd::load(p.lo), hi = simd::load(p.hi);
  r.geom.expand(lo, hi);
  f4 c = lo + hi;
  r.cent.expand(c, c);
}

// As add, but as if p were added before the primitives already in r's boxes.
inline void add_before(Range& r, const PrimRef& p) {
  f4 lo = simd::load(p.lo), hi = simd::load(p.hi);
  r.geom.expand_before(lo, hi);
  f4 c = lo + hi;
  r.cent.expand_before(c, c);
}

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

inline uint32_t blocks(uint32_t n) { return (n + 3) >> 2; }

struct BuildNode;

struct BuildChild {
  float lo[3], hi[3];
  BuildNode* node = nullptr;  // nullptr: a leaf of items [begin, end)
  uint32_t begin = 0, end = 0;
};

// Children per node of the 8-wide BVH.
constexpr int bvh_width = WideBvhNode::width;

struct BuildNode {
  BuildChild child[bvh_width];
  int n = 0;
  // Totals of the subtree (this node included), for the flattening offsets.
  uint32_t nodes = 0, packets = 0, triangles = 0;
  // >= 0: a stand-in for subtree `subtree` of a shared build, written by
  // another part and received flattened (n is 0; the totals are its own).
  int subtree = -1;
};

// A node of a shared build's top whose subtree one part builds: the range
// make_child had for it (with its split, when known: a range of more than
// max_leaf_ items is a node whatever its split, which its builder finds), and
// the child slot that points to it.
struct SubtreeTask {
  Range range;
  std::optional<Split> split;
  int depth = 0;
  BuildChild* slot = nullptr;
};

class MeshBuilder {
 public:
  MeshBuilder(std::vector<PrimRef>& refs, const BvhBuildOptions& o) : refs_(refs) {
    bins_per_axis_ = std::clamp(o.bins, 2, max_bins);
    max_leaf_ = std::clamp(o.max_leaf_size, 1, int(4 * WideBvhNode::max_leaf_packets));
    min_leaf_ = std::min(4, max_leaf_);
    traversal_cost_ = std::max(0.f, o.traversal_cost);
  }

  // The root node (always a node, even over a single leaf).
  BuildNode* build(const Range& root) {
    if (root.count() <= uint32_t(max_leaf_)) return single_leaf_root(root);
    Split s = find_split(root, 0);
    return build_node(root, s, 0);
  }

  // The top of the tree build() makes, for a build shared by `parts` parts:
  // the root node, opened as build_node opens it, and below it the interior
  // children that make_child would build, as tasks; where those would
  // balance badly over the parts (longest-processing-time first, by
  // triangles), the largest is opened in turn. `top` gets the nodes made
  // (parents before children), `tasks` the subtrees, depth first.
  void build_top(const Range& root, int parts, std::vector<BuildNode*>& top, std::vector<SubtreeTask>& tasks) {
    if (root.count() <= uint32_t(max_leaf_)) {
      top.push_back(single_leaf_root(root));
      return;
    }
    Split s = find_split(root, 0);
    top.push_back(open_top(root, s, 0, tasks));
    const int max_openings = 4 * parts;
    for (int opened = 0; opened < max_openings; ++opened) {
      if (tasks.empty()) break;
      std::vector<int> owner = assign_tasks(tasks, parts);
      std::vector<uint64_t> load(parts, 0);
      uint64_t total = 0;
      for (size_t t = 0; t < tasks.size(); ++t) {
        load[owner[t]] += tasks[t].range.count();
        total += tasks[t].range.count();
      }
      // Within a tenth of an even share: opening more would cost every part
      // more than the balance gains.
      if (10 * parts * *std::max_element(load.begin(), load.end()) <= 11 * total) break;
      size_t largest = 0;
      for (size_t t = 1; t < tasks.size(); ++t)
        if (tasks[t].range.count() > tasks[largest].range.count()) largest = t;
      SubtreeTask task = tasks[largest];
      std::vector<SubtreeTask> below;
      BuildNode* n = open_top(task.range, split_of(task), task.depth, below);
      task.slot->node = n;
      top.push_back(n);
      tasks.erase(tasks.begin() + std::ptrdiff_t(largest));
      tasks.insert(tasks.begin() + std::ptrdiff_t(largest), below.begin(), below.end());
    }
  }

  // Which part builds each task: largest first (ties: the earlier task), each
  // to the part with the fewest triangles so far (ties: the lower part).
  static std::vector<int> assign_tasks(const std::vector<SubtreeTask>& tasks, int parts) {
    std::vector<size_t> order(tasks.size());
    for (size_t t = 0; t < order.size(); ++t) order[t] = t;
    std::stable_sort(order.begin(), order.end(),
                     [&](size_t a, size_t b) { return tasks[a].range.count() > tasks[b].range.count(); });
    std::vector<uint64_t> load(parts, 0);
    std::vector<int> owner(tasks.size(), 0);
    for (size_t t : order) {
      int p = int(std::min_element(load.begin(), load.end()) - load.begin());
      owner[t] = p;
      load[p] += tasks[t].range.count();
    }
    return owner;
  }

  // The subtree of a task, as make_child would build it below its slot.
  BuildNode* build_task(const SubtreeTask& t) { return build_node(t.range, split_of(t), t.depth); }

  // The totals of a top node from its children's (stand-ins included).
  void refinish(BuildNode* n) const { finish(n); }

 private:
  static constexpr uint32_t parallel_threshold = 4096;  // smaller subtrees are built by one task
  static constexpr uint32_t parallel_bin_threshold = 1u << 15;
  // Beyond this depth, splits by count (each child at most half) keep the
  // tree within sah_depth_limit + 33 levels, which bounds the traversal stack.
  static constexpr int sah_depth_limit = 32;

  std::vector<PrimRef>& refs_;
  int bins_per_axis_, max_leaf_, min_leaf_;
  float traversal_cost_;
  tbb::enumerable_thread_specific<std::deque<BuildNode>> arenas_;

  BuildNode* new_node() { return &arenas_.local().emplace_back(); }

  BuildNode* single_leaf_root(const Range& root) {
    BuildNode* n = new_node();
    n->n = 1;
    n->child[0] = leaf(root);
    finish(n);
    return n;
  }

  // A node opened as build_node opens it, whose children are made as
  // make_child makes them but for the nodes below: those are left as tasks
  // (appended in child order), their splits too when they are sure to be
  // nodes (the top every part makes stays small).
  BuildNode* open_top(const Range& r, const Split& s, int depth, std::vector<SubtreeTask>& tasks) {
    Range child_ranges[bvh_width];
    const int k = open_node(r, s, depth, child_ranges);
    BuildNode* n = new_node();
    n->n = k;
    for (int i = 0; i < k; ++i) {
      BuildChild& c = n->child[i];
      Split split;
      if (child_ranges[i].count() > uint32_t(max_leaf_)) {
        set_bounds(c, child_ranges[i].geom);
        tasks.push_back({child_ranges[i], std::nullopt, depth + 1, &c});
      } else if (!leaf_or_split(child_ranges[i], depth + 1, c, split)) {
        tasks.push_back({child_ranges[i], split, depth + 1, &c});
      }
    }
    return n;
  }

  // The split make_child finds for a task's range (binning it for partition).
  Split split_of(const SubtreeTask& t) { return t.split ? *t.split : find_split(t.range, t.depth); }

  static void set_bounds(BuildChild& c, const Box& b) {
    float l[4], h[4];
    simd::store(l, b.lo);
    simd::store(h, b.hi);
    for (int a = 0; a < 3; ++a) {
      c.lo[a] = l[a];
      c.hi[a] = h[a];
    }
  }

  BuildChild leaf(const Range& r) const {
    BuildChild c;
    set_bounds(c, r.geom);
    c.begin = r.begin;
    c.end = r.end;
    return c;
  }

  void finish(BuildNode* n) const {
    n->nodes = 1;
    n->packets = 0;
    n->triangles = 0;
    for (int i = 0; i < n->n; ++i) {
      const BuildChild& c = n->child[i];
      if (c.node) {
        n->nodes += c.node->nodes;
        n->packets += c.node->packets;
        n->triangles += c.node->triangles;
      } else {
        n->packets += blocks(c.end - c.begin);
        n->triangles += c.end - c.begin;
      }
    }
  }

  // Bins refs_[begin, end) by their doubled centroids, and records each one's
  // bins in it for partition.
  void bin_range(uint32_t begin, uint32_t end, const f4& clo, const f4& scale, int nb, Bins& bins) {
    for (uint32_t i = begin; i < end; ++i) {
      PrimRef& p = refs_[i];
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
  }

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
    if (r.count() >= parallel_bin_threshold) {
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

  // Splits r by s (or, without a SAH split, by count) into two non-empty ranges.
  std::pair<Range, Range> partition(const Range& r, const Split& s) {
    Range left, right;
    uint32_t mid = r.begin + s.left;
    if (s.axis >= 0 && mid != r.begin && mid != r.end) {
      swap_misplaced(r, s);
      // The boxes as Hoare's partition accumulates them: [begin, mid) upwards,
      // [mid, end) downwards (which only matters where +0 and -0 tie).
      for (uint32_t i = r.begin; i < mid; ++i) add(left, refs_[i]);
      for (uint32_t i = mid; i < r.end; ++i) add_before(right, refs_[i]);
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

  // What make_child makes of range r: true and the leaf in c, or false, c's
  // bounds and the split of the node to build below c in s.
  bool leaf_or_split(const Range& r, int depth, BuildChild& c, Split& s) {
    if (r.count() <= uint32_t(min_leaf_)) {
      c = leaf(r);
      return true;
    }
    s = find_split(r, depth);
    if (r.count() <= uint32_t(max_leaf_) && float(blocks(r.count())) <= s.cost) {
      c = leaf(r);
      return true;
    }
    c = BuildChild{};
    set_bounds(c, r.geom);
    return false;
  }

  // A child for range r: a leaf, or a node built below it.
  BuildChild make_child(const Range& r, int depth) {
    BuildChild c;
    Split s;
    if (!leaf_or_split(r, depth, c, s)) c.node = build_node(r, s, depth);
    return c;
  }

  // Opens r into up to bvh_width ranges (returns how many), splitting the one
  // of largest area each time. r has more than min_leaf_ items, so it is split
  // at least once: a node never has r as its only child.
  int open_node(const Range& r, const Split& s, int depth, Range (&child_ranges)[bvh_width]) {
    std::optional<Split> child_splits[bvh_width];
    child_ranges[0] = r;
    child_splits[0] = s;
    int k = 1;
    while (k < bvh_width) {
      int best = -1;
      float best_area = -1.f;
      for (int i = 0; i < k; ++i) {
        if (child_ranges[i].count() <= uint32_t(min_leaf_)) continue;
        float a = child_ranges[i].geom.half_area();
        // An infinite extent times a zero one (a flat box spanning more than
        // the float range, such as a triangle at +-3e38 in a plane) is NaN,
        // which no comparison would pick: r would become its own only child,
        // again and again until the stack overflowed. Such a box is as large
        // as any.
        if (std::isnan(a)) a = infinity;
        if (a > best_area) {
          best_area = a;
          best = i;
        }
      }
      if (best < 0) break;
      if (!child_splits[best]) child_splits[best] = find_split(child_ranges[best], depth);
      auto [left, right] = partition(child_ranges[best], *child_splits[best]);
      child_ranges[best] = left;
      child_splits[best].reset();
      child_ranges[k] = right;
      child_splits[k].reset();
      ++k;
    }
    return k;
  }

  // Opens r (open_node), then builds below each child.
  BuildNode* build_node(const Range& r, const Split& s, int depth) {
    Range child_ranges[bvh_width];
    const int k = open_node(r, s, depth, child_ranges);
    BuildNode* n = new_node();
    n->n = k;
    if (r.count() >= parallel_threshold) {
      tbb::parallel_for(0, k, [&](int i) { n->child[i] = make_child(child_ranges[i], depth + 1); });
    } else {
      for (int i = 0; i < k; ++i) n->child[i] = make_child(child_ranges[i], depth + 1);
    }
    finish(n);
    return n;
  }
};

// Where a Flattener writes: the arrays of a MeshAccel, or of a subtree in a
// shared build's bytes.
// Packets are whole, or (packet_ids) only their four triangle ids each: the
// vertices are in every part's mesh, and a tenth of the bytes travel.
struct FlatArrays {
  WideBvhNode* nodes;
  TrianglePacket* packets;  // or nullptr and:
  uint32_t* packet_ids;     // 4 per packet
  uint32_t* triangles;
};

// A subtree of a shared build as a part sends it: flattened on its own, node
// references relative to its root and first packet, packets as their ids. The
// arrays point into the received bytes (unaligned).
struct FlatSubtree {
  uint32_t nodes = 0, packets = 0, triangles = 0;
  const std::byte* node_bytes = nullptr;
  const std::byte* packet_id_bytes = nullptr;  // 4 uint32 per packet
  const std::byte* triangle_bytes = nullptr;
};

// Writes the build tree depth first: a node, the packets of its leaf children,
// then its interior children's subtrees in order. Offsets come from the
// subtree totals, so subtrees are written in parallel and the result does not
// depend on the threads. A stand-in for a received subtree is copied there,
// its references rebased.
struct Flattener {
  const std::vector<PrimRef>& refs;
  std::span<const vec3> positions;
  std::span<const uint32_t> indices;
  FlatArrays out;
  std::span<const FlatSubtree> received = {};

  void copy_subtree(const FlatSubtree& s, uint32_t index, uint32_t packet, uint32_t tri) {
    std::memcpy(out.nodes + index, s.node_bytes, size_t(s.nodes) * sizeof(WideBvhNode));
    for (uint32_t k = 0; k < s.packets; ++k) {
      uint32_t ids[4];
      std::memcpy(ids, s.packet_id_bytes + sizeof ids * size_t(k), sizeof ids);
      fill_packet(out.packets[packet + k], ids);
    }
    std::memcpy(out.triangles + tri, s.triangle_bytes, size_t(s.triangles) * sizeof(uint32_t));
    for (uint32_t i = index; i < index + s.nodes; ++i)
      for (uint32_t& c : out.nodes[i].child) {
        if (!WideBvhNode::is_leaf(c)) c += index;
        else if (WideBvhNode::leaf_packet_count(c) > 0)  // empty slots stay leaf_ref(0, 0)
          c = WideBvhNode::leaf_ref(WideBvhNode::leaf_first_packet(c) + packet, WideBvhNode::leaf_packet_count(c));
      }
  }

  void fill_packet(TrianglePacket& p, const uint32_t (&ids)[4]) const {
    for (uint32_t lane = 0; lane < 4; ++lane) {
      const uint32_t t = ids[lane];
      p.id[lane] = t;
      for (int v = 0; v < 3; ++v) {
        const vec3& q = positions[indices[3 * size_t(t) + v]];
        for (int a = 0; a < 3; ++a) p.v[3 * v + a][lane] = q[a];
      }
    }
  }

  void write_leaf(uint32_t begin, uint32_t end, uint32_t packet, uint32_t tri) {
    uint32_t n = end - begin;
    for (uint32_t i = 0; i < n; ++i) out.triangles[tri + i] = refs[begin + i].id();
    for (uint32_t k = 0; k < blocks(n); ++k) {
      uint32_t ids[4];
      for (uint32_t lane = 0; lane < 4; ++lane)
        ids[lane] = refs[std::min(begin + 4 * k + lane, end - 1)].id();  // unused lanes repeat the last triangle
      if (out.packets) fill_packet(out.packets[packet + k], ids);
      else std::memcpy(out.packet_ids + 4 * size_t(packet + k), ids, sizeof ids);
    }
  }

  void write(const BuildNode* bn, uint32_t index, uint32_t packet, uint32_t tri) {
    if (bn->subtree >= 0) {
      copy_subtree(received[size_t(bn->subtree)], index, packet, tri);
      return;
    }
    WideBvhNode& o = out.nodes[index];
    uint32_t next_node = index + 1;
    struct Task {
      const BuildNode* node;
      uint32_t index, packet, tri;
    };
    Task tasks[bvh_width];
    int ntasks = 0;
    for (int i = 0; i < bvh_width; ++i) {
      if (i >= bn->n) {
        for (int a = 0; a < 3; ++a) {
          o.bounds[2 * a][i] = infinity;
          o.bounds[2 * a + 1][i] = -infinity;
        }
        o.child[i] = WideBvhNode::leaf_ref(0, 0);
        continue;
      }
      const BuildChild& c = bn->child[i];
      for (int a = 0; a < 3; ++a) {
        o.bounds[2 * a][i] = c.lo[a];
        o.bounds[2 * a + 1][i] = c.hi[a];
      }
      if (!c.node) {
        uint32_t np = blocks(c.end - c.begin);
        o.child[i] = WideBvhNode::leaf_ref(packet, np);
        write_leaf(c.begin, c.end, packet, tri);
        packet += np;
        tri += c.end - c.begin;
      }
    }
    for (int i = 0; i < bn->n; ++i) {
      const BuildChild& c = bn->child[i];
      if (!c.node) continue;
      o.child[i] = next_node;
      tasks[ntasks++] = {c.node, next_node, packet, tri};
      next_node += c.node->nodes;
      packet += c.node->packets;
      tri += c.node->triangles;
    }
    for (uint32_t& p : o.pad) p = 0;
    if (bn->triangles >= 8192 && ntasks > 1) {
      tbb::parallel_for(0, ntasks, [&](int t) { write(tasks[t].node, tasks[t].index, tasks[t].packet, tasks[t].tri); });
    } else {
      for (int t = 0; t < ntasks; ++t) write(tasks[t].node, tasks[t].index, tasks[t].packet, tasks[t].tri);
    }
  }
};

inline FlatArrays arrays(MeshAccel& m) { return {m.bvh.nodes.data(), m.packets.data(), nullptr, m.triangles.data()}; }

// The PrimRefs of the triangles with finite vertices, in index order, and
// the root range over them.
inline Range triangle_refs(std::span<const vec3> positions, std::span<const uint32_t> indices,
                           std::vector<PrimRef>& refs) {
  const size_t n = indices.size() / 3;
  // Triangle boxes, and the root range's boxes; triangles with a non-finite
  // vertex are left out (a NaN vertex would not even reach the box: min and
  // max pass over it).
  struct Boxes {
    size_t valid = 0;  // triangles with a box
    Range root;        // over those, in index order
  };
  refs.resize(n);
  Boxes boxes = tbb::parallel_reduce(
      tbb::blocked_range<size_t>(0, n, 1u << 14), Boxes{},
      [&](const tbb::blocked_range<size_t>& r, Boxes acc) {
        for (size_t i = r.begin(); i < r.end(); ++i) {
          Bounds3 b;
          bool ok = true;
          for (int k = 0; k < 3; ++k) {
            const vec3& v = positions[indices[3 * i + k]];
            b.expand(v);
            ok = ok && is_finite(v);
          }
          PrimRef& p = refs[i];
          for (int a = 0; a < 3; ++a) {
            p.lo[a] = b.lo[a];
            p.hi[a] = b.hi[a];
          }
          p.lo[3] = std::bit_cast<float>(uint32_t(i));
          p.hi[3] = ok ? 1.f : 0.f;
          if (ok) add(acc.root, p);
          acc.valid += ok;
        }
        return acc;
      },
      [](Boxes a, const Boxes& b) {
        a.valid += b.valid;
        a.root.geom.expand(b.root.geom);
        a.root.cent.expand(b.root.cent);
        return a;
      });
  if (boxes.valid != n) {
    refs.erase(std::remove_if(refs.begin(), refs.end(), [](const PrimRef& p) { return p.hi[3] == 0.f; }), refs.end());
  }
  Range root = boxes.root;
  root.end = uint32_t(refs.size());
  return root;
}

inline void check_packets(const BuildNode* tree) {
  if (tree->packets >= (1u << (31 - WideBvhNode::count_bits)))
    throw std::length_error("build_mesh_accel: too many triangle packets");
}

inline void set_root_bounds(MeshAccel& m, const Range& root) {
  float l[4], h[4];
  simd::store(l, root.geom.lo);
  simd::store(h, root.geom.hi);
  m.bvh.root_bounds = Bounds3{vec3(l[0], l[1], l[2]), vec3(h[0], h[1], h[2])};
}

// The build shared among the parts of `share` (mesh_accel_share.cpp).
MeshAccel build_shared(std::span<const vec3> positions, std::span<const uint32_t> indices,
                       const BvhBuildOptions& options, const WorkShare& share);

}  // namespace rayform::mesh_build
