// Acceleration structure of one triangle mesh in object space: a BVH over its
// triangles and the triangle vertices copied in leaf order, so that traversal
// touches one compact array (36 bytes a triangle) and never the Scene.
#pragma once

#include "accel/bvh.h"
#include "geometry/triangle_intersect.h"

#include <span>
#include <vector>

namespace rayform {

struct MeshAccel {
  Bvh bvh;
  std::vector<vec3> vertices;       // 3 per triangle, in bvh.primitives order
  std::vector<uint32_t> triangles;  // original triangle index, same order

  size_t memory_bytes() const {
    return bvh.memory_bytes() + vertices.capacity() * sizeof(vec3) + triangles.capacity() * sizeof(uint32_t);
  }
};

MeshAccel build_mesh_accel(std::span<const vec3> positions, std::span<const uint32_t> indices,
                           const BvhBuildOptions& options = {});

// Closest hit in the mesh; on success lowers tmax and fills the triangle index
// and barycentrics.
struct MeshHit {
  uint32_t triangle;
  float b0, b1, b2;
};

inline bool intersect_mesh(const MeshAccel& m, const Ray& ray, float& tmax, MeshHit* hit) {
  const TriangleRay tr = make_triangle_ray(ray);
  const vec3* v = m.vertices.data();
  return traverse_closest(m.bvh, ray, tmax, [&](uint32_t first, uint32_t count, float& t_max) {
    bool found = false;
    for (uint32_t i = first; i < first + count; ++i) {
      TriangleHit th;
      if (intersect_triangle(tr, v[3 * i], v[3 * i + 1], v[3 * i + 2], ray.tmin, t_max, &th)) {
        t_max = th.t;
        *hit = {m.triangles[i], th.b0, th.b1, th.b2};
        found = true;
      }
    }
    return found;
  });
}

inline bool occluded_mesh(const MeshAccel& m, const Ray& ray) {
  const TriangleRay tr = make_triangle_ray(ray);
  const vec3* v = m.vertices.data();
  return traverse_any(m.bvh, ray, [&](uint32_t first, uint32_t count) {
    for (uint32_t i = first; i < first + count; ++i) {
      TriangleHit th;
      if (intersect_triangle(tr, v[3 * i], v[3 * i + 1], v[3 * i + 2], ray.tmin, ray.tmax, &th)) return true;
    }
    return false;
  });
}

}  // namespace rayform
