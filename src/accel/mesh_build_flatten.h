// The MeshAccel builder's last step (mesh_accel_builder.h): the tree of
// BuildNodes written depth first into WideBvhNodes, TrianglePackets and
// triangle ids, subtrees in parallel, at offsets from the subtree totals.
#pragma once

#include "rayform/accel/mesh_build_tree.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <span>
#include <stdexcept>
#include <vector>

namespace rayform::mesh_build {

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

}  // namespace rayform::mesh_build
