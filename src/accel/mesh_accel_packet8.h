// Closest hits of eight rays at once through a MeshAccel (AVX2): camera rays
// of neighbouring pixels visit mostly the same nodes, so each node is read
// and tested once for all eight (a child's box against eight rays per vector
// operation), and the traversal's decisions are taken once per packet. The
// leaves test each ray that reaches them with the single-ray triangle test
// (intersect_packet) and the single-ray choice of the closest lane
// (pick_closest_lane), whose result does not depend on the order in which
// triangles are met: each ray gets exactly the hit intersect_mesh gives it.
//
// Private to mesh_accel_traverse.cpp, which includes this file once, after
// mesh_accel_kernel.h for the kernel_avx2 flavour, under
// #pragma GCC target("avx2"); the definitions are in kernel_avx2.
#pragma once

#include "rayform/accel/mesh_accel_node_test.h"
#include "rayform/accel/mesh_accel_packet_test.h"

#include <immintrin.h>

#include <algorithm>
#include <bit>
#include <cstdint>

namespace rayform {
namespace {
namespace kernel_avx2 {

// Per-ray constants of the slab test, one ray per lane.
struct NodeRay8 {
  __m256 org[3], inv[3], tmin;
};

// Closest hits of the rays in `active` (bit i: ray_list[i], lane i; r8 holds
// their slab constants), all of octant Oct. tmax[i] is lowered to the hit
// distance; found bits returned, hits[i] filled for them.
template <int Oct>
int intersect8_octant(const MeshAccel& m, const NodeRay8& r8, const Ray* ray_list, int active, float* tmax,
                      MeshHit* hits) {
  const WideBvhNode* nodes = m.bvh.nodes.data();
  const TrianglePacket* packets = m.packets.data();
  struct alignas(32) Entry {
    __m256 t;  // entry distance of each ray (+infinity where it misses the box)
    uint32_t ref;
    int rays;   // the rays that hit the box
    float key;  // t of the lowest of those rays: the order of visits
  };
  Entry stack[stack_size];
  int top = 0;
  uint32_t ref = 0;
  int rays = active;
  int found = 0;
  alignas(32) float tmax_lanes[8];
  for (int i = 0; i < 8; ++i) tmax_lanes[i] = tmax[i];
  __m256 tmax8 = _mm256_load_ps(tmax_lanes);
  uint32_t hit_slot[8] = {}, hit_id[8] = {};
  float hit_e[8][3] = {}, hit_inv[8] = {};
  // The triangle test's constants of a ray, made when it first reaches a leaf
  // (rays that miss every leaf never need them): bit i of tr_made for tr[i].
  TriRay tr[8];
  int tr_made = 0;
  const __m256 inf8 = _mm256_set1_ps(infinity), far8 = _mm256_set1_ps(far_scale);
  for (;;) {
    if (!WideBvhNode::is_leaf(ref)) {
      const WideBvhNode& n = nodes[ref];
      // Each child's box against the eight rays: the single-ray slab test, lane by lane.
      Entry children[WideBvhNode::width];
      int count = 0;
      for (int c = 0; c < WideBvhNode::width; ++c) {
        __m256 t0 = r8.tmin, t1 = inf8;
        for (int a = 0; a < 3; ++a) {
          const __m256 tn =
              _mm256_mul_ps(_mm256_sub_ps(_mm256_set1_ps(n.bounds[near_row<Oct>(a)][c]), r8.org[a]), r8.inv[a]);
          const __m256 tf =
              _mm256_mul_ps(_mm256_sub_ps(_mm256_set1_ps(n.bounds[far_row<Oct>(a)][c]), r8.org[a]), r8.inv[a]);
          t0 = _mm256_max_ps(tn, t0);
          t1 = _mm256_min_ps(tf, t1);
        }
        t1 = _mm256_min_ps(_mm256_mul_ps(t1, far8), tmax8);
        const __m256 hit = _mm256_cmp_ps(t0, t1, _CMP_LE_OQ);
        const int hit_rays = _mm256_movemask_ps(hit) & rays;
        if (!hit_rays) continue;
        alignas(32) float t[8];
        _mm256_store_ps(t, t0);
        children[count++] = {_mm256_blendv_ps(inf8, t0, hit), n.child[c], hit_rays,
                             t[std::countr_zero(unsigned(hit_rays))]};
      }
      if (count > 0) {
        // Nearest first (by key): push the others farthest first, go on with the nearest.
        int nearest = 0;
        for (int i = 1; i < count; ++i)
          if (children[i].key < children[nearest].key) nearest = i;
        const int base = top;
        for (int i = 0; i < count; ++i) {
          if (i == nearest) continue;
          const Entry e = children[i];
          int b = top++;
          // Insertion sort of the pushed entries, nearest on top.
          while (b > base) {
            if (!(stack[b - 1].key < e.key)) break;
            stack[b] = stack[b - 1];
            --b;
          }
          stack[b] = e;
          prefetch_child(nodes, packets, e.ref);
        }
        ref = children[nearest].ref;
        rays = children[nearest].rays;
        continue;
      }
    } else {
      const uint32_t first = WideBvhNode::leaf_first_packet(ref), count = WideBvhNode::leaf_packet_count(ref);
      int rest = rays;
      while (rest) {
        const int lane = pop_lowest_bit(rest);
        if (!((tr_made >> lane) & 1)) {
          tr[lane] = TriRay(ray_list[lane]);
          tr_made |= 1 << lane;
        }
        for (uint32_t k = first; k < first + count; ++k) {
          const PacketHits h = intersect_packet(packets[k], tr[lane], tmax_lanes[lane]);
          int best;
          if (!pick_closest_lane(h, k, (found >> lane) & 1, hit_slot[lane], &best)) continue;
          alignas(16) float ts[4], e0[4], e1[4], e2[4], inv[4];
          simd::store(ts, h.t);
          simd::store(e0, h.e0);
          simd::store(e1, h.e1);
          simd::store(e2, h.e2);
          simd::store(inv, h.inv_det);
          tmax_lanes[lane] = ts[best];
          hit_slot[lane] = packet_slot(k, best);
          hit_id[lane] = packets[k].id[best];
          hit_e[lane][0] = e0[best];
          hit_e[lane][1] = e1[best];
          hit_e[lane][2] = e2[best];
          hit_inv[lane] = inv[best];
          found |= 1 << lane;
        }
      }
      tmax8 = _mm256_load_ps(tmax_lanes);
    }
    // Pop the next entry that some ray still needs (entered before its closest hit).
    for (;;) {
      if (top == 0) {
        for (int i = 0; i < 8; ++i) {
          tmax[i] = tmax_lanes[i];
          if ((found >> i) & 1)
            hits[i] = {hit_id[i], hit_e[i][0] * hit_inv[i], hit_e[i][1] * hit_inv[i], hit_e[i][2] * hit_inv[i]};
        }
        return found;
      }
      const Entry& e = stack[--top];
      const int still = e.rays & _mm256_movemask_ps(_mm256_cmp_ps(e.t, tmax8, _CMP_LE_OQ));
      if (still) {
        ref = e.ref;
        rays = still;
        break;
      }
    }
  }
}

// Eight rays (those in `active`): the per-ray constants (the slab test's
// inverse directions eight at a time, the same divisions as make_ray_slabs),
// then the kernel of their octant. -1 when the active rays do not share one
// octant (nothing traced then).
inline int intersect8(const MeshAccel& m, const Ray* rays, int active, float* tmax, MeshHit* hits) {
  if (m.bvh.nodes.empty() || !active) return 0;
  alignas(32) float org[3][8], dir[3][8], tmin[8];
  for (int i = 0; i < 8; ++i) {
    for (int a = 0; a < 3; ++a) {
      org[a][i] = rays[i].origin[a];
      dir[a][i] = rays[i].direction[a];
    }
    tmin[i] = rays[i].tmin;
  }
  NodeRay8 r8;
  int oct = 0;
  for (int a = 0; a < 3; ++a) {
    r8.org[a] = _mm256_load_ps(org[a]);
    r8.inv[a] = _mm256_div_ps(_mm256_set1_ps(1.f), _mm256_load_ps(dir[a]));
    // make_ray_slabs' dir_is_neg: inv < 0, the same for every active ray or none.
    const int neg = _mm256_movemask_ps(_mm256_cmp_ps(r8.inv[a], _mm256_setzero_ps(), _CMP_LT_OQ)) & active;
    if (neg == active) oct |= 1 << a;
    else if (neg != 0) return -1;
  }
  r8.tmin = _mm256_load_ps(tmin);
  switch (oct) {
    case 0: return intersect8_octant<0>(m, r8, rays, active, tmax, hits);
    case 1: return intersect8_octant<1>(m, r8, rays, active, tmax, hits);
    case 2: return intersect8_octant<2>(m, r8, rays, active, tmax, hits);
    case 3: return intersect8_octant<3>(m, r8, rays, active, tmax, hits);
    case 4: return intersect8_octant<4>(m, r8, rays, active, tmax, hits);
    case 5: return intersect8_octant<5>(m, r8, rays, active, tmax, hits);
    case 6: return intersect8_octant<6>(m, r8, rays, active, tmax, hits);
    default: return intersect8_octant<7>(m, r8, rays, active, tmax, hits);
  }
}

}  // namespace kernel_avx2
}  // namespace
}  // namespace rayform
