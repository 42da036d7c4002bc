// Closest-hit and any-hit queries over a PreparedScene (hit first), and the
// surface data of a hit (shade after). Free functions over compact arrays: no
// virtual dispatch and no allocation per ray.
#pragma once

#include "rayform/geometry/plane_intersect.h"
#include "rayform/geometry/ray_offset.h"
#include "rayform/geometry/sphere_intersect.h"
#include "rayform/render/prepared_scene.h"

namespace rayform {

// Small hit record: which instance and primitive, where along the ray, and the
// barycentrics (b1, b2) of triangle hits.
struct Hit {
  float t = infinity;
  uint32_t instance = 0;
  uint32_t primitive = 0;
  float b1 = 0.f, b2 = 0.f;
};

// The ray in an instance's object space: M^-1 applied without renormalising,
// so t measures the same point in both spaces.
inline Ray to_object_space(const Instance& inst, const Ray& r) {
  if (!inst.has_transform) return r;
  Ray o = r;
  o.origin = transform_point(inst.to_object, r.origin);
  o.direction = transform_vector(inst.to_object, r.direction);
  return o;
}

// The hit record of a mesh instance's hit at t.
inline Hit mesh_instance_hit(uint32_t instance, float t, const MeshHit& mh) {
  return {t, instance, mh.triangle, mh.b1, mh.b2};
}

inline bool intersect_instance(const PreparedScene& p, uint32_t index, const Ray& world_ray, float& tmax, Hit* hit) {
  const Instance& inst = p.instances[index];
  Ray r = to_object_space(inst, world_ray);
  r.tmax = tmax;
  const Scene& s = *p.scene;
  switch (inst.kind) {
    case ShapeKind::sphere: {
      float t;
      if (!intersect_sphere(r, s.spheres[inst.shape].center, s.spheres[inst.shape].radius, &t)) return false;
      tmax = t;
      *hit = {t, index, 0, 0.f, 0.f};
      return true;
    }
    case ShapeKind::plane: {
      float t;
      if (!intersect_plane(r, s.planes[inst.shape].normal, s.planes[inst.shape].offset, &t)) return false;
      tmax = t;
      *hit = {t, index, 0, 0.f, 0.f};
      return true;
    }
    case ShapeKind::triangle: {
      const auto& v = s.triangles[inst.shape].vertices;
      TriangleHit th;
      if (!intersect_triangle(make_triangle_ray(r), v[0], v[1], v[2], r.tmin, r.tmax, &th)) return false;
      tmax = th.t;
      *hit = {th.t, index, 0, th.b1, th.b2};
      return true;
    }
    case ShapeKind::mesh: {
      MeshHit mh;
      if (!intersect_mesh(p.meshes[inst.shape], r, tmax, &mh)) return false;
      *hit = mesh_instance_hit(index, tmax, mh);
      return true;
    }
  }
  return false;
}

// Closest hit with ray.tmin < t < ray.tmax.
inline bool intersect_scene(const PreparedScene& p, const Ray& ray, Hit* hit) {
  float tmax = ray.tmax;
  bool found = traverse_bvh<BvhQuery::closest_hit>(p.top, ray, tmax, [&](uint32_t first, uint32_t count, float& t_max) {
    bool any = false;
    for (uint32_t i = first; i < first + count; ++i) any |= intersect_instance(p, p.top.primitives[i], ray, t_max, hit);
    return any;
  });
  for (uint32_t i : p.plane_instances) found |= intersect_instance(p, i, ray, tmax, hit);
  return found;
}

// The instance of a scene that consists of one mesh instance (no other shape,
// no plane), or -1. Camera rays of such a scene go through its mesh eight at a
// time (intersect_sole_mesh8).
inline int sole_mesh_instance(const PreparedScene& p) {
  if (!p.plane_instances.empty() || p.top.nodes.size() != 1 || p.top.nodes[0].count != 1) return -1;
  const uint32_t index = p.top.primitives[p.top.nodes[0].offset];
  return p.instances[index].kind == ShapeKind::mesh ? int(index) : -1;
}

// intersect_scene for eight rays (bit i of `active`: rays[i] is traced; all
// eight valid) of a scene whose sole_mesh_instance is `instance`: returns the
// bits of the rays that hit and fills their hits[i], each exactly what
// intersect_scene gives that ray.
inline int intersect_sole_mesh8(const PreparedScene& p, int instance, const Ray* rays, int active, Hit* hits) {
  const Instance& inst = p.instances[size_t(instance)];
  // Rays are copied only to transform them (a copy of eight rays through the
  // stack costs more than the packet's whole set-up).
  Ray transformed[8];
  const Ray* object_rays = rays;
  if (inst.has_transform) {  // as to_object_space, field by field; camera rays share their origin
    const vec3 origin0 = transform_point(inst.to_object, rays[0].origin);
    for (int i = 0; i < 8; ++i) {
      transformed[i].origin =
          rays[i].origin == rays[0].origin ? origin0 : transform_point(inst.to_object, rays[i].origin);
      transformed[i].direction = transform_vector(inst.to_object, rays[i].direction);
      transformed[i].tmin = rays[i].tmin;
      transformed[i].tmax = rays[i].tmax;
    }
    object_rays = transformed;
  }
  float tmax[8];
  for (int i = 0; i < 8; ++i) tmax[i] = rays[i].tmax;
  MeshHit mesh_hits[8];
  const int found = intersect_mesh8(p.meshes[size_t(inst.shape)], object_rays, active, tmax, mesh_hits);
  for (int i = 0; i < 8; ++i)
    if ((found >> i) & 1) hits[i] = mesh_instance_hit(uint32_t(instance), tmax[i], mesh_hits[i]);
  return found;
}

// Whether anything lies on the ray with tmin < t < tmax (shadow rays).
inline bool occluded(const PreparedScene& p, const Ray& ray) {
  auto blocks = [&](uint32_t index) {
    const Instance& inst = p.instances[index];
    if (inst.kind == ShapeKind::mesh) return occluded_mesh(p.meshes[inst.shape], to_object_space(inst, ray));
    float tmax = ray.tmax;
    Hit h;
    return intersect_instance(p, index, ray, tmax, &h);
  };
  for (uint32_t i : p.plane_instances)
    if (blocks(i)) return true;
  float tmax = ray.tmax;
  return traverse_bvh<BvhQuery::any_hit>(p.top, ray, tmax, [&](uint32_t first, uint32_t count, float&) {
    for (uint32_t i = first; i < first + count; ++i)
      if (blocks(p.top.primitives[i])) return true;
    return false;
  });
}

// Everything shading needs about a hit, in world space.
struct SurfacePoint {
  // The hit point, recomputed on the surface (barycentric point of the
  // triangle, or reprojected onto the sphere / plane) and transformed to world
  // space, and a conservative per-component bound on its absolute error: the
  // exact surface passes through [position - position_error, position +
  // position_error]. Secondary rays start at spawn_ray(position,
  // position_error, geometric_normal, w) (geometry/ray_offset.h). For
  // transformed instances the bound also covers the rounding of mapping a
  // spawned origin back to object space (object_roundtrip_error).
  vec3 position{0.f};
  vec3 position_error{0.f};
  vec3 normal{0.f, 0.f, 1.f};            // shading normal, unit length
  vec3 geometric_normal{0.f, 0.f, 1.f};  // unit length
  vec2 uv{0.f};
  bool has_uv = false;
  vec2 uv1{0.f};  // the second set (Mesh::uvs1)
  bool has_uv1 = false;
  // Tangent (xyz, world space, not normalised) and the bitangent's sign w
  // (Mesh::tangents convention, with w flipped where the instance's
  // transform mirrors), where the mesh has tangents (from the file or
  // generated at prepare for normal textures).
  vec4 tangent{0.f};
  bool has_tangent = false;
  vec3 color{1.f};  // vertex colour (1 when absent)
  int material = invalid;
};

// What surface_point computes of the hit point (the normals, uv, colour and
// material always).
enum class HitPoint {
  // position and a position_error that secondary rays can start from.
  spawn,
  // No secondary ray will start here: the bound of a transformed instance
  // leaves out the object-space round trip (the costliest part), so
  // position_error bounds only the point itself.
  point,
  // Neither (shading with directional lights only): position and
  // position_error stay zero.
  none,
};

SurfacePoint surface_point(const PreparedScene& p, const Ray& ray, const Hit& hit, HitPoint need = HitPoint::spawn);

}  // namespace rayform
