// Mesh BVHs kept from one prepare_scene to the next while the meshes do not
// change: a turntable renders copies of one loaded scene under other cameras
// and lights, and building its BVHs again for every frame was most of the
// frame's prepare (0.25-0.3 s for the 1M-triangle torus).
#pragma once

#include "rayform/accel/bvh.h"
#include "rayform/accel/mesh_accel.h"
#include "rayform/scene/scene.h"

#include <optional>
#include <vector>

namespace rayform {

struct PreparedScene;

struct MeshAccelCache {
  // The scene the kept BVHs are of (a turntable's loaded scene, which every
  // frame copies). It must outlive every use of the cache.
  const Scene* source = nullptr;
  // meshes[i], when set, is the BVH of source->meshes[i], built with `bvh`.
  BvhBuildOptions bvh;
  std::vector<std::optional<MeshAccel>> meshes;
};

// Whether two meshes have the same triangles: positions bit for bit, and indices.
bool same_triangles(const Mesh& a, const Mesh& b);

// The kept BVH of `scene.meshes[i]`, moved out of the cache, when it holds one
// for an equal mesh (same_triangles with source->meshes[i]) built with `bvh`.
std::optional<MeshAccel> take_cached_mesh_accel(MeshAccelCache& cache, const Scene& scene, size_t i,
                                                const BvhBuildOptions& bvh);

// After the last render of `prepared` (made by prepare_scene with `bvh`): its
// BVHs of meshes equal to the source's move into the cache, for the next
// frame's prepare_scene (PrepareOptions::cache); the cache's other entries are
// dropped. `prepared` must not be rendered again.
void keep_mesh_accels(PreparedScene& prepared, const BvhBuildOptions& bvh, MeshAccelCache& cache);

}  // namespace rayform
