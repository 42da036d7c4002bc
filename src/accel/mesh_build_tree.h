// The tree of the MeshAccel builder (mesh_accel_builder.h): an 8-wide tree of
// BuildNodes, each node opened into up to bvh_width child ranges (the largest
// split each time), subtrees built in parallel with oneTBB; and, for a build
// shared among parts, the top of that tree with the subtrees below it as
// tasks and which part builds each.
#pragma once

#include "rayform/accel/mesh_build_split.h"

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <deque>
#include <optional>
#include <vector>

namespace rayform::mesh_build {

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

// Builds the tree over a PrimRef array, which it reorders; the nodes live as
// long as the builder.
class MeshBuilder {
 public:
  MeshBuilder(std::vector<PrimRef>& refs, const BvhBuildOptions& o)
      : splitter_(refs, std::clamp(o.bins, 2, max_bins), std::max(0.f, o.traversal_cost)) {
    max_leaf_ = std::clamp(o.max_leaf_size, 1, int(4 * WideBvhNode::max_leaf_packets));
    min_leaf_ = std::min(4, max_leaf_);
  }

  // The root node (always a node, even over a single leaf).
  BuildNode* build(const Range& root) {
    if (root.count() <= uint32_t(max_leaf_)) return single_leaf_root(root);
    Split s = splitter_.find_split(root, 0);
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
    Split s = splitter_.find_split(root, 0);
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

  RangeSplitter splitter_;
  int max_leaf_, min_leaf_;
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
  Split split_of(const SubtreeTask& t) { return t.split ? *t.split : splitter_.find_split(t.range, t.depth); }

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

  // What make_child makes of range r: true and the leaf in c, or false, c's
  // bounds and the split of the node to build below c in s.
  bool leaf_or_split(const Range& r, int depth, BuildChild& c, Split& s) {
    if (r.count() <= uint32_t(min_leaf_)) {
      c = leaf(r);
      return true;
    }
    s = splitter_.find_split(r, depth);
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
      if (!child_splits[best]) child_splits[best] = splitter_.find_split(child_ranges[best], depth);
      auto [left, right] = splitter_.partition(child_ranges[best], *child_splits[best]);
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

}  // namespace rayform::mesh_build
