// Counts and bounds of a scene, for `rayform info` and for framing default cameras.
#pragma once

#include "rayform/geometry/bounds.h"
#include "rayform/base/limits.h"
#include "rayform/scene/scene.h"

#include <string>

namespace rayform {

struct SceneStats {
  size_t nodes = 0, instances = 0;  // instances: shape nodes after flattening
  size_t spheres = 0, planes = 0, triangles = 0, meshes = 0;
  size_t mesh_triangles = 0;         // over all instances (a mesh instanced twice counts twice)
  size_t unique_mesh_triangles = 0;  // over the meshes themselves
  size_t materials = 0, textures = 0, lights = 0, cameras = 0;
  Bounds3 bounds;  // world bounds of the bounded shapes (planes excluded)
};

// Throws rayform::Error when the node graph is invalid (cycle, bad index) or
// makes more than `max_instances` shape instances.
SceneStats scene_stats(const Scene& scene, uint64_t max_instances = Limits{}.instances);

// Human-readable summary, one item a line.
std::string format_scene_stats(const SceneStats& s);

// Mesh counts over the scene's meshes (each once).
struct MeshTotals {
  size_t vertices = 0, uvs = 0, normals = 0, triangles = 0;
};
MeshTotals mesh_totals(const Scene& scene);

}  // namespace rayform
