#include "rayform/scene/scene_stats.h"

#include "rayform/scene/node_walk.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <sstream>

namespace rayform {
namespace {

// The bounds of `points`, by parallel tasks over blocks joined in order: the
// same bounds as expanding by each point in turn (where +0 and -0 tie, the
// first point's).
Bounds3 bounds_of(const std::vector<vec3>& points) {
  constexpr size_t block = size_t(1) << 15;
  const size_t blocks = (points.size() + block - 1) / block;
  std::vector<Bounds3> parts(blocks);
  tbb::parallel_for(size_t(0), blocks, [&](size_t b) {
    const size_t end = std::min(points.size(), (b + 1) * block);
    for (size_t i = b * block; i < end; ++i) parts[b].expand(points[i]);
  });
  Bounds3 all;
  for (const Bounds3& part : parts) all.expand(part);
  return all;
}

}  // namespace

SceneStats scene_stats(const Scene& scene, uint64_t max_instances) {
  SceneStats st;
  st.nodes = scene.nodes.size();
  st.spheres = scene.spheres.size();
  st.planes = scene.planes.size();
  st.triangles = scene.triangles.size();
  st.meshes = scene.meshes.size();
  st.materials = scene.materials.size();
  st.textures = scene.textures.size();
  st.lights = scene.lights.size();
  st.cameras = scene.cameras.size();
  for (const Mesh& m : scene.meshes) st.unique_mesh_triangles += m.triangle_count();
  // Object-space bounds of each mesh, computed once however many instances use it.
  std::vector<Bounds3> mesh_bounds(scene.meshes.size());
  std::vector<uint8_t> mesh_bounded(scene.meshes.size(), 0);
  for_each_shape_node(
      scene,
      [&](const Node& n, const mat4& m) {
        st.instances++;
        switch (n.shape_kind) {
          case ShapeKind::sphere: {
            if (n.shape < 0 || n.shape >= int(scene.spheres.size())) break;
            const Sphere& s = scene.spheres[n.shape];
            Bounds3 b;
            b.expand(s.center - vec3(std::abs(s.radius)));
            b.expand(s.center + vec3(std::abs(s.radius)));
            st.bounds.expand(transform_bounds(m, b));
            break;
          }
          case ShapeKind::triangle:
            if (n.shape < 0 || n.shape >= int(scene.triangles.size())) break;
            for (const vec3& v : scene.triangles[n.shape].vertices) st.bounds.expand(transform_point(m, v));
            break;
          case ShapeKind::mesh: {
            if (n.shape < 0 || n.shape >= int(scene.meshes.size())) break;
            const Mesh& mesh = scene.meshes[n.shape];
            st.mesh_triangles += mesh.triangle_count();
            Bounds3& b = mesh_bounds[size_t(n.shape)];
            if (!mesh_bounded[size_t(n.shape)]) {
              b = bounds_of(mesh.positions);
              mesh_bounded[size_t(n.shape)] = 1;
            }
            if (!b.empty()) st.bounds.expand(transform_bounds(m, b));
            break;
          }
          case ShapeKind::plane: break;
        }
      },
      max_instances);
  return st;
}

std::string format_scene_stats(const SceneStats& s) {
  std::ostringstream o;
  o << "nodes:       " << s.nodes << "\n"
    << "instances:   " << s.instances << "\n"
    << "spheres:     " << s.spheres << "\n"
    << "planes:      " << s.planes << "\n"
    << "triangles:   " << s.triangles << " standalone, " << s.mesh_triangles << " in " << s.meshes << " meshes ("
    << s.unique_mesh_triangles << " unique)\n"
    << "materials:   " << s.materials << "\n"
    << "textures:    " << s.textures << "\n"
    << "lights:      " << s.lights << "\n"
    << "cameras:     " << s.cameras << "\n";
  if (s.bounds.empty()) o << "bounds:      empty\n";
  else
    o << "bounds:      (" << s.bounds.lo.x << ", " << s.bounds.lo.y << ", " << s.bounds.lo.z << ") - (" << s.bounds.hi.x
      << ", " << s.bounds.hi.y << ", " << s.bounds.hi.z << ")" << (s.planes ? " (planes excluded)" : "") << "\n";
  return o.str();
}

MeshTotals mesh_totals(const Scene& scene) {
  MeshTotals t;
  for (const Mesh& m : scene.meshes) {
    t.vertices += m.positions.size();
    t.uvs += m.uvs.size();
    t.normals += m.normals.size();
    t.triangles += m.triangle_count();
  }
  return t;
}

}  // namespace rayform
