// The build of a MeshAccel shared among the parts of a WorkShare
// (build_mesh_accel in mesh_accel.h): every part makes the triangle boxes and
// the top of the tree, builds the subtrees assigned to it, and after one
// exchange assembles the whole structure, byte for byte the whole build's.
#include "rayform/accel/mesh_accel_builder.h"

#include <cstdint>
#include <cstring>
#include <deque>
#include <exception>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace rayform::mesh_build {
namespace {

// The bytes of a packet's ids in a shared build's exchange.
constexpr size_t packet_ids_size = 4 * sizeof(uint32_t);

// A shared build's subtree header: its totals, and where its arrays start in
// the part's bytes.
struct SubtreeHeader {
  uint32_t nodes, packets, triangles, pad;
  uint64_t node_at, packet_at, triangle_at;
};

}  // namespace

// The shared build (see build_mesh_accel in mesh_accel.h). A part's bytes: a
// flag (1: its subtrees follow; 0: it failed), then a SubtreeHeader per
// subtree it built, in task order, then their arrays: nodes, packets as
// their ids (every part fills in the vertices), triangles.
MeshAccel build_shared(std::span<const vec3> positions, std::span<const uint32_t> indices,
                       const BvhBuildOptions& options, const WorkShare& share) {
  std::vector<PrimRef> refs;
  Range root;
  std::optional<MeshBuilder> builder;  // made in the try below: its allocations may fail too
  std::vector<BuildNode*> top;
  std::vector<SubtreeTask> tasks;
  std::vector<int> owner;
  std::vector<std::byte> mine;
  std::exception_ptr failure;
  // Whatever this part meets here (an allocation failing), it takes part in
  // the one exchange, which tells the others.
  try {
    root = triangle_refs(positions, indices, refs);
    builder.emplace(refs, options);
    if (!refs.empty()) builder->build_top(root, share.parts, top, tasks);
    owner = MeshBuilder::assign_tasks(tasks, share.parts);
    std::vector<size_t> own;
    for (size_t t = 0; t < tasks.size(); ++t)
      if (owner[t] == share.part) own.push_back(t);
    std::vector<const BuildNode*> built(own.size());
    tbb::parallel_for(size_t(0), own.size(), [&](size_t i) { built[i] = builder->build_task(tasks[own[i]]); });
    // The flag, the headers, then each subtree's arrays, flattened in place,
    // each from a 64-byte boundary of memory (WideBvhNode's alignment).
    const size_t header_bytes = 1 + own.size() * sizeof(SubtreeHeader);
    constexpr size_t align = alignof(WideBvhNode);
    size_t most = header_bytes + align;
    for (const BuildNode* b : built)
      most += size_t(b->nodes) * sizeof(WideBvhNode) + size_t(b->packets) * packet_ids_size +
              size_t(b->triangles) * sizeof(uint32_t) + 3 * align;
    mine.resize(most);
    const uintptr_t base = reinterpret_cast<uintptr_t>(mine.data());
    auto aligned = [&](size_t at) { return size_t((base + at + align - 1) / align * align - base); };
    std::vector<SubtreeHeader> headers(own.size());
    size_t at = header_bytes;
    for (size_t i = 0; i < own.size(); ++i) {
      SubtreeHeader& h = headers[i];
      h = {built[i]->nodes, built[i]->packets, built[i]->triangles, 0, 0, 0, 0};
      h.node_at = aligned(at);
      h.packet_at = aligned(h.node_at + size_t(h.nodes) * sizeof(WideBvhNode));
      h.triangle_at = aligned(h.packet_at + size_t(h.packets) * packet_ids_size);
      at = h.triangle_at + size_t(h.triangles) * sizeof(uint32_t);
    }
    mine.resize(at);  // smaller: the data stay where they are
    mine[0] = std::byte{1};
    if (!headers.empty()) std::memcpy(mine.data() + 1, headers.data(), headers.size() * sizeof(SubtreeHeader));
    tbb::parallel_for(size_t(0), own.size(), [&](size_t i) {
      const SubtreeHeader& h = headers[i];
      const FlatArrays out{reinterpret_cast<WideBvhNode*>(mine.data() + h.node_at), nullptr,
                           reinterpret_cast<uint32_t*>(mine.data() + h.packet_at),
                           reinterpret_cast<uint32_t*>(mine.data() + h.triangle_at)};
      Flattener{refs, positions, indices, out}.write(built[i], 0, 0, 0);
    });
  } catch (...) {
    failure = std::current_exception();
    mine.assign(1, std::byte{0});
  }
  const std::vector<std::vector<std::byte>> all = share.exchange(std::move(mine));
  if (failure) std::rethrow_exception(failure);
  if (all.size() != size_t(share.parts)) throw std::logic_error("build_mesh_accel: the exchange lost parts");
  for (int p = 0; p < share.parts; ++p)
    if (all[p].empty() || all[p][0] != std::byte{1})
      throw std::runtime_error("build_mesh_accel: part " + std::to_string(p) + " of a shared build failed");

  MeshAccel m;
  if (refs.empty()) return m;
  // Each task's subtree from its part's bytes, and a stand-in node for it.
  std::vector<FlatSubtree> received(tasks.size());
  std::vector<size_t> seen(share.parts, 0);  // subtrees read from each part
  for (size_t t = 0; t < tasks.size(); ++t) {
    const std::vector<std::byte>& b = all[owner[t]];
    const size_t k = seen[owner[t]]++;
    SubtreeHeader h;
    if (b.size() < 1 + (k + 1) * sizeof h) throw std::logic_error("build_mesh_accel: a part's bytes end early");
    std::memcpy(&h, b.data() + 1 + k * sizeof h, sizeof h);
    if (h.node_at > b.size() || (b.size() - h.node_at) / sizeof(WideBvhNode) < h.nodes || h.packet_at > b.size() ||
        (b.size() - h.packet_at) / packet_ids_size < h.packets || h.triangle_at > b.size() ||
        (b.size() - h.triangle_at) / sizeof(uint32_t) < h.triangles)
      throw std::logic_error("build_mesh_accel: a part's bytes end early");
    received[t] = {
        h.nodes, h.packets, h.triangles, b.data() + h.node_at, b.data() + h.packet_at, b.data() + h.triangle_at};
  }
  std::deque<BuildNode> stand_ins;
  for (size_t t = 0; t < tasks.size(); ++t) {
    BuildNode& n = stand_ins.emplace_back();
    n.subtree = int(t);
    n.nodes = received[t].nodes;
    n.packets = received[t].packets;
    n.triangles = received[t].triangles;
    tasks[t].slot->node = &n;
  }
  for (auto it = top.rbegin(); it != top.rend(); ++it) builder->refinish(*it);  // children before parents
  const BuildNode* tree = top.front();
  check_packets(tree);
  m.bvh.nodes.resize(tree->nodes);
  m.packets.resize(tree->packets);
  m.triangles.resize(tree->triangles);
  Flattener{refs, positions, indices, arrays(m), received}.write(tree, 0, 0, 0);
  set_root_bounds(m, root);
  return m;
}

}  // namespace rayform::mesh_build
