// Traversal kernels of MeshAccel: closest hit (intersect) and any hit
// (occluded), each instantiated for the eight octants of the ray direction
// (constant plane rows in the node test). The triangle side comes from
// mesh_accel_packet_test.h (TriRay, intersect_packet), the node side from
// mesh_accel_node_test.h (NodeRay, node_hits<Oct>, octant, pop_lowest_bit,
// prefetch_child, stack_size).
//
// No include guard: mesh_accel_traverse.cpp includes this file once per
// node-test flavour, defining RAYFORM_MESH_KERNEL_FLAVOUR to the namespace of
// mesh_accel_node_test.h whose NodeRay and node_hits the kernels use
// (kernel_portable, the default, or kernel_avx2, included under
// #pragma GCC target("avx2")); the kernels are defined in that namespace.
#include "rayform/accel/mesh_accel.h"
#include "rayform/accel/mesh_accel_node_test.h"
#include "rayform/accel/mesh_accel_packet_test.h"
#include "rayform/accel/simd4.h"
#include "rayform/geometry/bounds.h"
#include "rayform/geometry/ray.h"

#include <bit>
#include <cstdint>
#include <type_traits>
#include <utility>

#ifndef RAYFORM_MESH_KERNEL_FLAVOUR
#define RAYFORM_MESH_KERNEL_FLAVOUR kernel_portable
#endif

namespace rayform {
namespace {
namespace RAYFORM_MESH_KERNEL_FLAVOUR {

// node_hits with the node's child references prefetched meanwhile (they are
// read only after the box test).
template <int Oct>
inline int children_hit(const WideBvhNode& n, const NodeRay& nr, float tmax, float* t_enter) {
#if defined(__GNUC__)
  __builtin_prefetch(n.child);
#endif
  return node_hits<Oct>(n, nr, tmax, t_enter);
}

// Which hit of a packet becomes the closest one, if any: the lane with the
// smallest t below tmax (the lowest lane of equal ones), or else, among lanes
// at exactly t == tmax, the lowest one if its slot comes before that of the hit
// found so far. So the closest hit is the smallest (t, slot) over all the
// triangles the ray hits, whatever order the traversal meets them in (the
// packet traversal of mesh_accel_packet8.h meets them in another). Ties are
// rare: rays through an edge or vertex shared by triangles of equal t.
inline uint32_t packet_slot(uint32_t packet, int lane) { return 4 * packet + uint32_t(lane) + 1; }

inline bool pick_closest_lane(const PacketHits& h, uint32_t packet, bool found, uint32_t hit_slot, int* best) {
  if (h.mask) {
    alignas(16) float ts[4];
    simd::store(ts, h.t);
    int rest = h.mask;
    *best = pop_lowest_bit(rest);
    while (rest) {
      int lane = pop_lowest_bit(rest);
      if (ts[lane] < ts[*best]) *best = lane;
    }
    return true;
  }
  if (!found || !h.tie_mask) return false;
  *best = std::countr_zero(unsigned(h.tie_mask));
  return packet_slot(packet, *best) < hit_slot;
}

// One traversal, two queries. closest_hit: nearest child first, the others
// pushed with their entry distance and skipped when popped behind the closest
// hit found meanwhile; *hit set when it returns true. any_hit: children in
// index order, stops at the first hit (hit unused).
template <int Oct, BvhQuery query>
inline bool traverse_octant(const MeshAccel& m, const NodeRay& nr, const TriRay& tr, float& tmax, MeshHit* hit) {
  constexpr bool any_hit = query == BvhQuery::any_hit;
  const WideBvhNode* nodes = m.bvh.nodes.data();
  const TrianglePacket* packets = m.packets.data();
  struct Entry {
    uint32_t ref;
    float t;
  };
  // any_hit never compares entry distances, so its stack holds references only.
  using StackEntry = std::conditional_t<any_hit, uint32_t, Entry>;
  StackEntry stack[stack_size];
  int top = 0;
  uint32_t ref = 0;
  bool found = false;
  uint32_t hit_slot = 0;  // packet_slot of the hit found
  uint32_t hit_id = 0;
  float hit_e[3] = {0.f, 0.f, 0.f}, hit_inv = 0.f;
  for (;;) {
    if (!WideBvhNode::is_leaf(ref)) {
      const WideBvhNode& n = nodes[ref];
      alignas(32) float tn[WideBvhNode::width];
      int mask = children_hit<Oct>(n, nr, tmax, tn);
      if (mask != 0) {
        int i = pop_lowest_bit(mask);
        if constexpr (any_hit) {
          while (mask) {
            int k = pop_lowest_bit(mask);
            stack[top++] = n.child[k];
            prefetch_child(nodes, packets, n.child[k]);
          }
          ref = n.child[i];
          continue;
        } else {
          if (mask == 0) {  // one child hit: go on without the stack
            ref = n.child[i];
            continue;
          }
          int j = pop_lowest_bit(mask);
          if (mask == 0) {  // two: the nearer first
            if (tn[j] < tn[i]) std::swap(i, j);
            prefetch_child(nodes, packets, n.child[j]);
            stack[top++] = {n.child[j], tn[j]};
            ref = n.child[i];
            continue;
          }
          // More: push all, sorted so that the nearest is on top, and pop it.
          const int base = top;
          stack[top++] = {n.child[i], tn[i]};
          stack[top++] = {n.child[j], tn[j]};
          while (mask) {
            int k = pop_lowest_bit(mask);
            stack[top++] = {n.child[k], tn[k]};
          }
          for (int a = base; a < top - 1; ++a) prefetch_child(nodes, packets, stack[a].ref);
          for (int a = base + 1; a < top; ++a) {  // insertion sort, descending t
            Entry e = stack[a];
            int b = a;
            while (b > base && stack[b - 1].t < e.t) {
              stack[b] = stack[b - 1];
              --b;
            }
            stack[b] = e;
          }
          ref = stack[--top].ref;
          continue;
        }
      }
    } else {
      const uint32_t first = WideBvhNode::leaf_first_packet(ref), count = WideBvhNode::leaf_packet_count(ref);
      for (uint32_t k = first; k < first + count; ++k) {
        PacketHits h = intersect_packet(packets[k], tr, tmax);
        int best;
        if constexpr (any_hit) {
          if (h.mask) return true;
          continue;
        } else if (!pick_closest_lane(h, k, found, hit_slot, &best)) {
          continue;
        }
        alignas(16) float ts[4];
        simd::store(ts, h.t);
        tmax = ts[best];
        hit_slot = packet_slot(k, best);
        alignas(16) float e0[4], e1[4], e2[4], inv[4];
        simd::store(e0, h.e0);
        simd::store(e1, h.e1);
        simd::store(e2, h.e2);
        simd::store(inv, h.inv_det);
        hit_id = packets[k].id[best];
        hit_e[0] = e0[best];
        hit_e[1] = e1[best];
        hit_e[2] = e2[best];
        hit_inv = inv[best];
        found = true;
      }
    }
    // Pop the next entry (closest_hit: the next still in front of the closest hit).
    if constexpr (any_hit) {
      if (top == 0) return false;
      ref = stack[--top];
    } else {
      for (;;) {
        if (top == 0) {
          if (found) *hit = {hit_id, hit_e[0] * hit_inv, hit_e[1] * hit_inv, hit_e[2] * hit_inv};
          return found;
        }
        const Entry& e = stack[--top];
        if (e.t <= tmax) {
          ref = e.ref;
          break;
        }
      }
    }
  }
}

// The ray's octant as a template argument (constant plane rows in the node test).
template <BvhQuery query>
inline bool traverse(const MeshAccel& m, const Ray& ray, float& tmax, MeshHit* hit) {
  if (m.bvh.nodes.empty()) return false;
  const RaySlabs s = make_ray_slabs(ray);
  const NodeRay nr(s, ray.tmin);
  const TriRay tr(ray);
  switch (octant(s)) {
    case 0: return traverse_octant<0, query>(m, nr, tr, tmax, hit);
    case 1: return traverse_octant<1, query>(m, nr, tr, tmax, hit);
    case 2: return traverse_octant<2, query>(m, nr, tr, tmax, hit);
    case 3: return traverse_octant<3, query>(m, nr, tr, tmax, hit);
    case 4: return traverse_octant<4, query>(m, nr, tr, tmax, hit);
    case 5: return traverse_octant<5, query>(m, nr, tr, tmax, hit);
    case 6: return traverse_octant<6, query>(m, nr, tr, tmax, hit);
    default: return traverse_octant<7, query>(m, nr, tr, tmax, hit);
  }
}

inline bool intersect(const MeshAccel& m, const Ray& ray, float& tmax, MeshHit* hit) {
  return traverse<BvhQuery::closest_hit>(m, ray, tmax, hit);
}

inline bool occluded(const MeshAccel& m, const Ray& ray) {
  float tmax = ray.tmax;
  return traverse<BvhQuery::any_hit>(m, ray, tmax, nullptr);
}

}  // namespace RAYFORM_MESH_KERNEL_FLAVOUR
}  // namespace
}  // namespace rayform

#undef RAYFORM_MESH_KERNEL_FLAVOUR
