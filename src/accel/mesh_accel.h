// Acceleration structure of one triangle mesh in object space: an 8-wide BVH
// (eight child boxes per node, tested together with SIMD) whose leaves hold
// packets of four triangles with their vertices stored SoA, so that traversal
// touches two compact arrays and never the Scene. The triangle test is the
// watertight one of geometry/triangle_intersect.h, evaluated four triangles at
// a time with the very same float operations (bit-identical results, but for
// the early accept of hits in front of every vertex: see intersect_packet in
// mesh_accel_packet_test.h). Built in mesh_accel_build.cpp, traversed in
// mesh_accel_traverse.cpp.
#pragma once

#include "rayform/accel/bvh.h"
#include "rayform/accel/huge_page_allocator.h"
#include "rayform/geometry/triangle_intersect.h"
#include "rayform/base/work_share.h"

#include <cstdint>
#include <span>
#include <vector>

namespace rayform {

// A node of the 8-wide BVH: the boxes of its eight children SoA (bounds[0] =
// lo.x of children 0..7, then hi.x, lo.y, hi.y, lo.z, hi.z) and a reference
// per child. Unused slots have empty boxes (lo = +inf, hi = -inf), which no
// ray hits. 256 bytes, four cache lines.
struct alignas(64) WideBvhNode {
  static constexpr int width = 8;
  float bounds[6][width];
  uint32_t child[width];
  uint32_t pad[width];

  // Child references: an interior node index, or a leaf (top bit set) of
  // leaf_packet_count(ref) consecutive packets from leaf_first_packet(ref).
  static constexpr uint32_t leaf_bit = 0x80000000u;
  static constexpr int count_bits = 4;
  static constexpr uint32_t max_leaf_packets = (1u << count_bits) - 1;
  static bool is_leaf(uint32_t ref) { return (ref & leaf_bit) != 0; }
  static uint32_t leaf_ref(uint32_t first_packet, uint32_t packets) {
    return leaf_bit | (first_packet << count_bits) | packets;
  }
  static uint32_t leaf_first_packet(uint32_t ref) { return (ref & ~leaf_bit) >> count_bits; }
  static uint32_t leaf_packet_count(uint32_t ref) { return ref & max_leaf_packets; }
};
static_assert(sizeof(WideBvhNode) == 256);

// Four triangles, vertices SoA: v[3 * k + a][lane] is coordinate a of vertex
// k of triangle `lane`, id[lane] its original index. A leaf's last packet
// repeats its last triangle in the unused lanes (the duplicate never wins:
// ties go to the lowest lane).
struct alignas(16) TrianglePacket {
  float v[9][4];
  uint32_t id[4];
};
static_assert(sizeof(TrianglePacket) == 160);

// Nodes and packets are read at random by incoherent rays: on huge pages when
// large (huge_page_allocator.h).
struct WideBvh {
  std::vector<WideBvhNode, HugePageAllocator<WideBvhNode>> nodes;  // nodes[0] is the root (absent for an empty mesh)
  Bounds3 root_bounds;
  Bounds3 bounds() const { return root_bounds; }
  size_t memory_bytes() const { return nodes.capacity() * sizeof(WideBvhNode); }
};

struct MeshAccel {
  WideBvh bvh;
  std::vector<TrianglePacket, HugePageAllocator<TrianglePacket>> packets;  // leaf order
  std::vector<uint32_t> triangles;  // original triangle index, leaf order (one per triangle; not
                                    // needed by traversal, which reads TrianglePacket::id)

  // The arrays' capacities in bytes, as Embree's memory monitor counts its
  // blocks: a huge-page array's mapping ends on a whole 2 MiB page, up to
  // 2 MiB more per array than counted here.
  size_t memory_bytes() const {
    return bvh.memory_bytes() + packets.capacity() * sizeof(TrianglePacket) + triangles.capacity() * sizeof(uint32_t);
  }
};

// Builds with a parallel (oneTBB) binned SAH builder; deterministic: the same
// input gives the same structure whatever the number of threads. Triangles
// with a non-finite (NaN or infinite) vertex are left out. options.max_leaf_size bounds
// the triangles of a leaf (clamped to 1..60; leaves are made of packets of
// four), options.bins the SAH bins per axis (clamped to 2..64; fewer for
// small ranges), options.traversal_cost the cost of a node relative to a
// packet test. Throws std::length_error for a mesh too large for the
// references (2^31 triangles or 2^27 packets).
//
// With a shared `share` (share->parts > 1) and a mesh of at least
// options.share_min_triangles triangles, the build is shared among the parts:
// every part computes the triangle boxes and the top of the tree (the root
// node, opened further where its subtrees would balance badly over the
// parts), builds the subtrees below it assigned to its part, and one
// share->exchange gives every part the others' subtrees, from which it
// assembles the very MeshAccel an unshared build gives, byte for byte.
// Collective: every part must call it with the same mesh and options, and
// make its shared builds in the same order. A part that fails still takes
// part in the exchange; then every part throws (the failed one its own error).
MeshAccel build_mesh_accel(std::span<const vec3> positions, std::span<const uint32_t> indices,
                           const BvhBuildOptions& options = {}, const WorkShare* share = nullptr);

// A hit on a mesh triangle: its original index (indices[3 * triangle + k] are
// its vertices) and its barycentrics (the hit point is b0*p0 + b1*p1 + b2*p2,
// as in TriangleHit).
struct MeshHit {
  uint32_t triangle;
  float b0, b1, b2;
};

// Closest hit in the mesh with ray.tmin < t < tmax (the ray's own tmax is not
// used); on success lowers tmax to the hit's t, fills *hit and returns true,
// else leaves both unchanged.
bool intersect_mesh(const MeshAccel& m, const Ray& ray, float& tmax, MeshHit* hit);

// Closest hits of eight rays (bit i of `active`: rays[i] is traced; all
// eight must be valid rays): for each traced ray exactly what intersect_mesh
// gives it with tmax[i]. Returns the bits of the rays that hit, lowers their
// tmax[i] and fills their hits[i]. When the traced rays share the octant of
// their direction (camera rays of neighbouring pixels) and the CPU has AVX2,
// they go through the tree together; otherwise one by one.
int intersect_mesh8(const MeshAccel& m, const Ray* rays, int active, float* tmax, MeshHit* hits);

// Whether some triangle lies on the ray with ray.tmin < t < ray.tmax.
bool occluded_mesh(const MeshAccel& m, const Ray& ray);

}  // namespace rayform
