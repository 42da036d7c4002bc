#include "rayform/render/scene_intersect.h"

namespace rayform {

SurfacePoint surface_point(const PreparedScene& p, const Ray& ray, const Hit& hit, HitPoint need) {
  const Instance& inst = p.instances[hit.instance];
  const Scene& s = *p.scene;
  SurfacePoint sp;
  sp.material = inst.material;
  // The hit point in object space with its error bound (geometry/ray_offset.h).
  PointError pe;
  const bool point = need != HitPoint::none;
  vec3 n_obj{0.f, 0.f, 1.f}, ng_obj{0.f, 0.f, 1.f};
  switch (inst.kind) {
    case ShapeKind::sphere: {
      const Sphere& sph = s.spheres[inst.shape];
      const vec3 p_obj = to_object_space(inst, ray).at(hit.t);
      n_obj = ng_obj = (p_obj - sph.center) / sph.radius;
      if (point) pe = sphere_point(p_obj, sph.center, sph.radius);
      break;
    }
    case ShapeKind::plane: {
      const Plane& pl = s.planes[inst.shape];
      n_obj = ng_obj = pl.normal;
      if (point) pe = plane_point(to_object_space(inst, ray).at(hit.t), pl.normal, pl.offset);
      break;
    }
    case ShapeKind::triangle: {
      const auto& v = s.triangles[inst.shape].vertices;
      n_obj = ng_obj = glm::cross(v[1] - v[0], v[2] - v[0]);
      if (point) pe = triangle_point(v[0], v[1], v[2], 1.f - hit.b1 - hit.b2, hit.b1, hit.b2);
      break;
    }
    case ShapeKind::mesh: {
      const Mesh& m = s.meshes[inst.shape];
      uint32_t i0 = m.indices[3 * hit.primitive], i1 = m.indices[3 * hit.primitive + 1],
               i2 = m.indices[3 * hit.primitive + 2];
      float b1 = hit.b1, b2 = hit.b2, b0 = 1.f - b1 - b2;
      ng_obj = glm::cross(m.positions[i1] - m.positions[i0], m.positions[i2] - m.positions[i0]);
      if (point) pe = triangle_point(m.positions[i0], m.positions[i1], m.positions[i2], b0, b1, b2);
      n_obj = m.normals.empty() ? ng_obj : b0 * m.normals[i0] + b1 * m.normals[i1] + b2 * m.normals[i2];
      if (!m.uvs.empty()) {
        sp.uv = b0 * m.uvs[i0] + b1 * m.uvs[i1] + b2 * m.uvs[i2];
        sp.has_uv = true;
      }
      if (!m.uvs1.empty()) {
        sp.uv1 = b0 * m.uvs1[i0] + b1 * m.uvs1[i1] + b2 * m.uvs1[i2];
        sp.has_uv1 = true;
      }
      if (!m.tangents.empty()) {
        sp.tangent = b0 * m.tangents[i0] + b1 * m.tangents[i1] + b2 * m.tangents[i2];
        sp.tangent.w = m.tangents[i0].w;
        sp.has_tangent = true;
      } else if (!p.corner_tangents[size_t(inst.shape)].empty()) {
        const vec4* c = &p.corner_tangents[size_t(inst.shape)][3 * size_t(hit.primitive)];
        sp.tangent = b0 * c[0] + b1 * c[1] + b2 * c[2];
        sp.tangent.w = c[0].w;
        sp.has_tangent = true;
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
    if (sp.has_tangent) {  // a direction: the linear part; a mirroring transform flips the handedness
      const vec3 t = mat3(inst.to_world) * vec3(sp.tangent);
      sp.tangent = vec4(t, glm::determinant(mat3(inst.to_world)) < 0.f ? -sp.tangent.w : sp.tangent.w);
    }
    n_obj = inst.normal_to_world * n_obj;
    ng_obj = inst.normal_to_world * ng_obj;
    if (point) pe = transform_point(inst.to_world, pe);
  }
  if (inst.has_transform && need == HitPoint::spawn) {
    // Spawned rays are intersected in object space again: cover the rounding
    // of that mapping too, for any origin within an offset of the point.
    const vec3 e0 = object_roundtrip_error(inst.to_world, inst.to_object, glm::abs(pe.p) + pe.error);
    const float reach = (pe.error.x + e0.x) + (pe.error.y + e0.y) + (pe.error.z + e0.z);
    pe.error += object_roundtrip_error(inst.to_world, inst.to_object, glm::abs(pe.p) + 2.f * reach);
  }
  if (point && is_finite(pe.p) && is_finite(pe.error)) {
    sp.position = pe.p;
    sp.position_error = pe.error;
  } else if (point) {  // degenerate data (overflow): the point on the ray, with no usable bound
    sp.position = ray.at(hit.t);
    sp.position_error = vec3(infinity);
  }
  // A zero-length normal (degenerate data) falls back to facing the ray.
  float ln = glm::length(n_obj), lg = glm::length(ng_obj);
  sp.geometric_normal = lg > 0.f && std::isfinite(lg) ? ng_obj / lg : -glm::normalize(ray.direction);
  sp.normal = ln > 0.f && std::isfinite(ln) ? n_obj / ln : sp.geometric_normal;
  return sp;
}

}  // namespace rayform
