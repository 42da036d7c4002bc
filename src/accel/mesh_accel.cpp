#include "accel/mesh_accel.h"

namespace rayform {

MeshAccel build_mesh_accel(std::span<const vec3> positions, std::span<const uint32_t> indices,
                           const BvhBuildOptions& options) {
  size_t n = indices.size() / 3;
  std::vector<Bounds3> bounds(n);
  for (size_t i = 0; i < n; ++i) {
    Bounds3 b;
    for (int k = 0; k < 3; ++k) b.expand(positions[indices[3 * i + k]]);
    bounds[i] = b;
  }
  MeshAccel m;
  m.bvh = build_bvh(bounds, options);
  m.vertices.resize(m.bvh.primitives.size() * 3);
  m.triangles.resize(m.bvh.primitives.size());
  for (size_t i = 0; i < m.bvh.primitives.size(); ++i) {
    uint32_t t = m.bvh.primitives[i];
    m.triangles[i] = t;
    for (int k = 0; k < 3; ++k) m.vertices[3 * i + k] = positions[indices[3 * t + k]];
  }
  // Leaves now address `vertices` directly: the primitive list is no longer needed.
  m.bvh.primitives.clear();
  m.bvh.primitives.shrink_to_fit();
  return m;
}

}  // namespace rayform
