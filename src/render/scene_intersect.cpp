#include "render/scene_intersect.h"

namespace rayform {

SurfacePoint surface_point(const PreparedScene& p, const Ray& ray, const Hit& hit) {
  const Instance& inst = p.instances[hit.instance];
  const Scene& s = *p.scene;
  SurfacePoint sp;
  sp.material = inst.material;
  sp.position = ray.at(hit.t);
  vec3 n_obj{0.f, 0.f, 1.f}, ng_obj{0.f, 0.f, 1.f};
  switch (inst.kind) {
    case ShapeKind::sphere: {
      const Sphere& sph = s.spheres[inst.shape];
      Ray r = to_object_space(inst, ray);
      n_obj = ng_obj = (r.at(hit.t) - sph.center) / sph.radius;
      break;
    }
    case ShapeKind::plane: n_obj = ng_obj = s.planes[inst.shape].normal; break;
    case ShapeKind::triangle: {
      const auto& v = s.triangles[inst.shape].vertices;
      n_obj = ng_obj = glm::cross(v[1] - v[0], v[2] - v[0]);
      break;
    }
    case ShapeKind::mesh: {
      const Mesh& m = s.meshes[inst.shape];
      uint32_t i0 = m.indices[3 * hit.primitive], i1 = m.indices[3 * hit.primitive + 1],
               i2 = m.indices[3 * hit.primitive + 2];
      float b1 = hit.b1, b2 = hit.b2, b0 = 1.f - b1 - b2;
      ng_obj = glm::cross(m.positions[i1] - m.positions[i0], m.positions[i2] - m.positions[i0]);
      n_obj = m.normals.empty() ? ng_obj : b0 * m.normals[i0] + b1 * m.normals[i1] + b2 * m.normals[i2];
      if (!m.uvs.empty()) {
        sp.uv = b0 * m.uvs[i0] + b1 * m.uvs[i1] + b2 * m.uvs[i2];
        sp.has_uv = true;
      }
      if (!m.colors.empty()) sp.color = b0 * m.colors[i0] + b1 * m.colors[i1] + b2 * m.colors[i2];
      if (!m.face_materials.empty()) {
        int fm = m.face_materials[hit.primitive];
        if (fm >= 0 && fm < int(s.materials.size())) sp.material = fm;
      }
      break;
    }
  }
  if (inst.has_transform) {
    n_obj = inst.normal_to_world * n_obj;
    ng_obj = inst.normal_to_world * ng_obj;
  }
  // A zero-length normal (degenerate data) falls back to facing the ray.
  float ln = glm::length(n_obj), lg = glm::length(ng_obj);
  vec3 facing = -glm::normalize(ray.direction);
  sp.geometric_normal = lg > 0.f && std::isfinite(lg) ? ng_obj / lg : facing;
  sp.normal = ln > 0.f && std::isfinite(ln) ? n_obj / ln : sp.geometric_normal;
  return sp;
}

}  // namespace rayform
