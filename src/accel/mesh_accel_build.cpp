// build_mesh_accel (mesh_accel.h): the whole build, or the shared one
// (mesh_accel_share.cpp) for a large mesh and a WorkShare of several parts.
// The builder itself is in mesh_accel_builder.h.
#include "rayform/accel/mesh_accel.h"

#include "rayform/accel/mesh_accel_builder.h"

#include <stdexcept>

namespace rayform {
namespace mesh_build {
namespace {

MeshAccel build_whole(std::span<const vec3> positions, std::span<const uint32_t> indices,
                      const BvhBuildOptions& options) {
  MeshAccel m;
  std::vector<PrimRef> refs;
  const Range root = triangle_refs(positions, indices, refs);
  if (refs.empty()) return m;
  MeshBuilder builder(refs, options);
  const BuildNode* tree = builder.build(root);
  check_packets(tree);
  m.bvh.nodes.resize(tree->nodes);
  m.packets.resize(tree->packets);
  m.triangles.resize(tree->triangles);
  Flattener{refs, positions, indices, arrays(m)}.write(tree, 0, 0, 0);
  set_root_bounds(m, root);
  return m;
}

}  // namespace
}  // namespace mesh_build

MeshAccel build_mesh_accel(std::span<const vec3> positions, std::span<const uint32_t> indices,
                           const BvhBuildOptions& options, const WorkShare* share) {
  if (indices.size() / 3 >= (size_t(1) << 31)) throw std::length_error("build_mesh_accel: too many triangles");
  // The same decision on every part: it depends only on the mesh's size and the options.
  if (share && share->shared() && indices.size() / 3 >= options.share_min_triangles)
    return mesh_build::build_shared(positions, indices, options, *share);
  return mesh_build::build_whole(positions, indices, options);
}

}  // namespace rayform
