#include "rayform/render/mesh_accel_cache.h"

#include "rayform/render/prepared_scene.h"

#include <cstring>

namespace rayform {
namespace {

template <class T>
bool same_bytes(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

}  // namespace

bool same_triangles(const Mesh& a, const Mesh& b) {
  return same_bytes(a.indices, b.indices) && same_bytes(a.positions, b.positions);
}

std::optional<MeshAccel> take_cached_mesh_accel(MeshAccelCache& cache, const Scene& scene, size_t i,
                                                const BvhBuildOptions& bvh) {
  if (!cache.source || !(cache.bvh == bvh) || i >= cache.meshes.size() || !cache.meshes[i] ||
      i >= cache.source->meshes.size() || i >= scene.meshes.size() ||
      !same_triangles(cache.source->meshes[i], scene.meshes[i]))
    return std::nullopt;
  std::optional<MeshAccel> kept = std::move(cache.meshes[i]);
  cache.meshes[i].reset();
  return kept;
}

void keep_mesh_accels(PreparedScene& prepared, const BvhBuildOptions& bvh, MeshAccelCache& cache) {
  cache.bvh = bvh;
  cache.meshes.clear();
  if (!cache.source || !prepared.scene) return;
  const Scene& scene = *prepared.scene;
  cache.meshes.resize(prepared.meshes.size());
  for (size_t i = 0; i < prepared.meshes.size(); ++i) {
    MeshAccel& accel = prepared.meshes[i];
    if (accel.bvh.nodes.empty() && accel.packets.empty()) continue;  // not used, not built
    if (i < scene.meshes.size() && i < cache.source->meshes.size() &&
        same_triangles(scene.meshes[i], cache.source->meshes[i]))
      cache.meshes[i] = std::move(accel);
  }
}

}  // namespace rayform
