// The node side of MeshAccel traversal, for the kernels of mesh_accel_kernel.h:
// the slab test of an 8-wide node's child boxes in two flavours (NodeRay and
// node_hits<Oct> in namespace kernel_portable, four lanes at a time, and in
// kernel_avx2, eight at once, when RAYFORM_HAVE_AVX2_KERNEL), the direction
// octant that picks the near and far plane rows, and what visiting the
// children needs (pop_lowest_bit over the hit mask, prefetch_child, the stack
// bound). Private to mesh_accel_traverse.cpp, whose one translation unit
// includes it (the definitions have internal linkage).
#pragma once

#include "rayform/accel/mesh_accel.h"
#include "rayform/accel/simd4.h"
#include "rayform/geometry/bounds.h"
#include "rayform/math/math.h"

#include <bit>
#include <cstdint>

#if RAYFORM_SIMD4_SSE
#include <immintrin.h>
#endif

namespace rayform {
namespace {

using simd::f4;

// The slab test's far distances are scaled up by this (bounds.h, slab_hit).
constexpr float far_scale = 1.f + 2.f * gamma_bound(3);

// Deep enough for any tree the builder makes (at most 66 levels of nodes, see
// MeshBuilder::sah_depth_limit in mesh_accel_build.cpp), each pushing at most
// width - 1 entries.
constexpr int stack_size = 66 * (WideBvhNode::width - 1) + 1;

// The index of mask's lowest set bit (mask != 0), which is cleared.
inline int pop_lowest_bit(int& mask) {
  const int i = std::countr_zero(unsigned(mask));
  mask &= mask - 1;
  return i;
}

// Asks for the memory of a child before it is visited (traversal is bound by
// cache misses on incoherent rays): a node's four cache lines, or the first
// packet of a leaf.
inline void prefetch_child(const WideBvhNode* nodes, const TrianglePacket* packets, uint32_t ref) {
#if defined(__GNUC__)
  const char* p;
  int lines;
  if (WideBvhNode::is_leaf(ref)) {
    p = reinterpret_cast<const char*>(packets + WideBvhNode::leaf_first_packet(ref));
    lines = 3;
  } else {
    p = reinterpret_cast<const char*>(nodes + ref);
    lines = 4;
  }
  for (int i = 0; i < lines; ++i) __builtin_prefetch(p + 64 * i);
#else
  (void)nodes;
  (void)packets;
  (void)ref;
#endif
}

// The octant of a ray's direction: bit a set when the slab test takes the
// far side first on axis a (make_ray_slabs' dir_is_neg). The kernels are
// instantiated per octant, so that the rows of the near and far planes are
// constants: bounds[near_row<Oct>(a)], bounds[far_row<Oct>(a)].
inline int octant(const RaySlabs& s) { return s.dir_is_neg[0] | s.dir_is_neg[1] << 1 | s.dir_is_neg[2] << 2; }
template <int Oct>
constexpr int near_row(int a) {
  return 2 * a + ((Oct >> a) & 1);
}
template <int Oct>
constexpr int far_row(int a) {
  return 2 * a + 1 - ((Oct >> a) & 1);
}

// Per-ray constants of the slab test, for the portable node test.
struct NodeRay4 {
  f4 org[3], inv[3];
  float tmin;
  NodeRay4(const RaySlabs& s, float ray_tmin) {
    for (int a = 0; a < 3; ++a) {
      org[a] = simd::splat(s.origin[a]);
      inv[a] = simd::splat(s.inv_dir[a]);
    }
    tmin = ray_tmin;
  }
};

// The slab test of bounds.h (slab_hit) on the eight boxes of a node, as two
// halves of four: the same operations lane by lane (the far scale applied to
// the minimum of the far distances, which rounds the same as scaling each).
// Returns the mask of boxes hit and writes their entry distances.
namespace kernel_portable {
using NodeRay = NodeRay4;
template <int Oct>
inline int node_hits(const WideBvhNode& n, const NodeRay& r, float tmax, float* t_enter) {
  int mask = 0;
  for (int half = 0; half < 2; ++half) {
    f4 t0 = simd::splat(r.tmin), t1 = simd::splat(infinity);
    for (int a = 0; a < 3; ++a) {
      f4 tn = (simd::load(&n.bounds[near_row<Oct>(a)][4 * half]) - r.org[a]) * r.inv[a];
      f4 tf = (simd::load(&n.bounds[far_row<Oct>(a)][4 * half]) - r.org[a]) * r.inv[a];
      t0 = simd::vmax(tn, t0);
      t1 = simd::vmin(tf, t1);
    }
    t1 = simd::vmin(t1 * simd::splat(far_scale), simd::splat(tmax));
    simd::store(t_enter + 4 * half, t0);
    mask |= simd::mask_bits(t0 <= t1) << (4 * half);
  }
  return mask;
}
}  // namespace kernel_portable

}  // namespace
}  // namespace rayform

#if RAYFORM_SIMD4_SSE && defined(__GNUC__) && (defined(__x86_64__) || defined(__i386__))
#define RAYFORM_HAVE_AVX2_KERNEL 1
#pragma GCC push_options
#pragma GCC target("avx2")
namespace rayform {
namespace {
namespace kernel_avx2 {
struct NodeRay {
  __m256 org[3], inv[3];
  float tmin;
  NodeRay(const RaySlabs& s, float ray_tmin) {
    for (int a = 0; a < 3; ++a) {
      org[a] = _mm256_set1_ps(s.origin[a]);
      inv[a] = _mm256_set1_ps(s.inv_dir[a]);
    }
    tmin = ray_tmin;
  }
};
// As kernel_portable::node_hits, eight lanes at once (AVX: max/min/compare
// have the same lane semantics as their SSE forms).
template <int Oct>
inline int node_hits(const WideBvhNode& n, const NodeRay& r, float tmax, float* t_enter) {
  __m256 t0 = _mm256_set1_ps(r.tmin), t1 = _mm256_set1_ps(infinity);
  for (int a = 0; a < 3; ++a) {
    __m256 tn = _mm256_mul_ps(_mm256_sub_ps(_mm256_load_ps(n.bounds[near_row<Oct>(a)]), r.org[a]), r.inv[a]);
    __m256 tf = _mm256_mul_ps(_mm256_sub_ps(_mm256_load_ps(n.bounds[far_row<Oct>(a)]), r.org[a]), r.inv[a]);
    t0 = _mm256_max_ps(tn, t0);
    t1 = _mm256_min_ps(tf, t1);
  }
  t1 = _mm256_min_ps(_mm256_mul_ps(t1, _mm256_set1_ps(far_scale)), _mm256_set1_ps(tmax));
  _mm256_storeu_ps(t_enter, t0);
  return _mm256_movemask_ps(_mm256_cmp_ps(t0, t1, _CMP_LE_OQ));
}
}  // namespace kernel_avx2
}  // namespace
}  // namespace rayform
#pragma GCC pop_options
#endif
