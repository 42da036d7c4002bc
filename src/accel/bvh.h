// Bounding volume hierarchy over abstract primitives given by their bounds:
// binned SAH build, nodes flattened depth-first (the left child follows its
// parent), traversed near child first with a small explicit stack. It serves
// the instances of a scene (the top level); the triangles of a mesh have their
// own 8-wide BVH (mesh_accel.h), built with the same options.
#pragma once

#include "rayform/geometry/bounds.h"

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace rayform {

// 32 bytes. Leaf: count > 0, primitives [offset, offset + count) of
// Bvh::primitives. Interior: count == 0, left child at index + 1, right child
// at `offset`, `axis` the split axis (for near-child-first order).
struct BvhNode {
  vec3 lo;
  uint32_t offset;
  vec3 hi;
  uint16_t count;
  uint8_t axis;
  uint8_t pad;
};
static_assert(sizeof(BvhNode) == 32);

struct Bvh {
  std::vector<BvhNode> nodes;
  std::vector<uint32_t> primitives;  // primitive ids in leaf order
  Bounds3 bounds() const { return nodes.empty() ? Bounds3{} : Bounds3{nodes[0].lo, nodes[0].hi}; }
  size_t memory_bytes() const { return nodes.capacity() * sizeof(BvhNode) + primitives.capacity() * sizeof(uint32_t); }
};

// The builder never makes a tree deeper than this, so traversal stacks of
// this size cannot overflow (each level pushes at most one extra entry).
inline constexpr int bvh_max_depth = 120;
inline constexpr int bvh_stack_size = bvh_max_depth + 2;

struct BvhBuildOptions {
  // Leaves never hold more than this many primitives. Mesh BVHs: up to two
  // 4-triangle packets (the SAH decides; fewer nodes and faster random rays
  // than with one, docs/performance.md); the top level asks for 1.
  int max_leaf_size = 8;
  int bins = 16;               // SAH candidate planes per axis
  float traversal_cost = 1.f;  // relative to one primitive test (mesh BVH: one test of a 4-triangle packet)
  // build_mesh_accel with a WorkShare: meshes of at least this many triangles
  // are built shared among its parts (smaller ones whole by each part: the
  // exchange copies the arrays, and the parts wait for each other there).
  // Half this size gained nothing shared over two ranks, this size did
  // (docs/distributed.md).
  size_t share_min_triangles = size_t(1) << 15;
  bool operator==(const BvhBuildOptions&) const = default;
};

// Builds a BVH; primitives with empty bounds are left out. Deterministic.
Bvh build_bvh(std::span<const Bounds3> primitive_bounds, const BvhBuildOptions& options = {});

enum class BvhQuery {
  closest_hit,  // near child first; leaves may lower tmax; returns whether any leaf reported a hit
  any_hit,      // children in index order; stops at the first leaf that reports a hit (shadow rays)
};

// Depth-first traversal with a small explicit stack. `leaf(first, count, tmax)`
// tests primitives [first, first+count) of bvh.primitives with
// ray.tmin < t < tmax, may lower tmax (closest_hit), and returns whether it hit.
template <BvhQuery query, class LeafFn>
inline bool traverse_bvh(const Bvh& bvh, const Ray& ray, float& tmax, LeafFn&& leaf) {
  if (bvh.nodes.empty()) return false;
  // A root leaf (a handful of primitives, e.g. one mesh): its box test would
  // only repeat theirs.
  if (bvh.nodes[0].count > 0) return leaf(bvh.nodes[0].offset, bvh.nodes[0].count, tmax);
  const RaySlabs slabs = make_ray_slabs(ray);
  const BvhNode* nodes = bvh.nodes.data();
  uint32_t stack[bvh_stack_size];
  int top = 0;
  stack[top++] = 0;
  bool hit = false;
  float t_enter;
  while (top > 0) {
    uint32_t index = stack[--top];
    const BvhNode& n = nodes[index];
    // Tested on pop, so that a closer hit found meanwhile prunes the node.
    if (!slab_hit(n.lo, n.hi, slabs, ray.tmin, tmax, &t_enter)) continue;
    if (n.count > 0) {
      if (leaf(n.offset, n.count, tmax)) {
        if constexpr (query == BvhQuery::any_hit) return true;
        hit = true;
      }
    } else if (query == BvhQuery::closest_hit && slabs.dir_is_neg[n.axis]) {  // the right child is nearer
      stack[top++] = index + 1;
      stack[top++] = n.offset;
    } else {
      stack[top++] = n.offset;
      stack[top++] = index + 1;
    }
  }
  return hit;
}

}  // namespace rayform
