// The glTF writer's cameras, lights and background (GltfWriter,
// gltf_writer_internal.h): each camera and KHR_lights_punctual light on a node of its
// own, what glTF cannot say about it in its extras; the background in the
// scene's extras.
#include "rayform/importers/gltf/gltf_writer_internal.h"
#include "rayform/importers/shape_tessellation.h"

#include <glm/gtc/quaternion.hpp>

#include <algorithm>
#include <cmath>

namespace rayform::gltf_detail {

namespace {

// Rotation (x, y, z, w) of a right-handed orthonormal basis (columns).
std::vector<double> quaternion(const mat3& basis) {
  glm::dquat q = glm::quat_cast(glm::dmat3(basis));
  q = glm::normalize(q);
  return {q.x, q.y, q.z, q.w};
}

// A basis whose -z axis is `dir` (and whose y axis is as close to `up` as can be).
mat3 look_basis(vec3 dir, vec3 up) {
  vec3 w = glm::normalize(dir);
  vec3 u = glm::cross(w, up);
  if (!(glm::length(u) > 1e-6f)) u = glm::cross(w, std::abs(w.y) < 0.9f ? vec3(0, 1, 0) : vec3(1, 0, 0));
  u = glm::normalize(u);
  vec3 v = glm::cross(u, w);
  return mat3(u, v, -w);
}

}  // namespace

std::string GltfWriter::unique_name(const std::string& wanted, std::set<std::string>& used) {
  std::string n = wanted;
  for (int k = 2; used.count(n); ++k) n = wanted + "_" + std::to_string(k);
  used.insert(n);
  return n;
}

int GltfWriter::add_camera(int ci) {
  const Camera& c = scene_.cameras[size_t(ci)];
  tinygltf::Camera gc;
  gc.name = unique_name(c.name.empty() ? "camera" : c.name, camera_names_);
  const float reach = 4.f * plane_quad_scale * extent_radius_ + glm::length(c.center - extent_center_);
  if (c.projection == Camera::Projection::perspective) {
    gc.type = "perspective";
    gc.perspective.yfov = double(radians(c.fov_deg));
    gc.perspective.znear = nice(1e-3f * extent_radius_);
    gc.perspective.zfar = nice(reach);
  } else {
    gc.type = "orthographic";
    gc.orthographic.xmag = nice(0.5f * c.ortho_height);
    gc.orthographic.ymag = nice(0.5f * c.ortho_height);
    gc.orthographic.znear = 0.0;
    gc.orthographic.zfar = nice(reach);
  }
  Value::Object ex;
  ex["name"] = Value(c.name);
  ex["aspect"] = Value(std::string(c.aspect == Camera::Aspect::stretch ? "stretch" : "fit"));
  ex["up_vector"] = Value(std::string(c.up_vector == Camera::UpVector::raw ? "raw" : "orthonormal"));
  ex["center"] = vec_value(c.center);
  ex["direction"] = vec_value(c.direction);
  ex["up"] = vec_value(c.up);
  ex["fov_deg"] = num(c.fov_deg);
  ex["ortho_height"] = num(c.ortho_height);
  gc.extras = rayform_extras(std::move(ex));
  if (c.aspect == Camera::Aspect::stretch) ++stretched_;
  if (c.up_vector == Camera::UpVector::raw) {
    vec3 w = glm::normalize(c.direction);
    vec3 v = glm::cross(glm::normalize(glm::cross(w, c.up)), w);
    if (glm::length(c.up - v) > 1e-6f) ++raw_up_;
  }
  model_.cameras.push_back(std::move(gc));
  tinygltf::Node n;
  n.name = model_.cameras.back().name;
  n.camera = int(model_.cameras.size()) - 1;
  n.translation = nice_vector({c.center.x, c.center.y, c.center.z});
  n.rotation = quaternion(look_basis(c.direction, c.up));
  return add_node(std::move(n));
}

int GltfWriter::add_light(int li) {
  const Light& l = scene_.lights[size_t(li)];
  tinygltf::Light gl;
  gl.name = unique_name(l.name.empty() ? "light" : l.name, light_names_);
  float peak = std::max({l.color.r, l.color.g, l.color.b});
  vec3 color = peak > 0.f ? l.color / peak : vec3(1.f);
  float intensity = peak > 0.f ? peak : 0.f;
  if (peak > 0.f && peak <= 1.f) {  // keep colours in [0, 1] as they are
    color = l.color;
    intensity = 1.f;
  }
  color = glm::clamp(color, vec3(0.f), vec3(1.f));
  switch (l.kind) {
    case Light::Kind::directional: gl.type = "directional"; break;
    case Light::Kind::point: gl.type = "point"; break;
    case Light::Kind::spot: gl.type = "spot"; break;
  }
  if (l.kind != Light::Kind::directional) {
    if (l.falloff > 0.f) {
      // colour / (falloff d^2) = (intensity / d^2) x colour_gltf
      intensity /= l.falloff;
    } else {
      // No attenuation: match at the centre of the scene.
      float d = extent_.empty() ? 1.f : glm::length(extent_center_ - l.position);
      if (!(d > 0.f)) d = 1.f;
      intensity *= d * d;
      ++no_falloff_;
    }
    if (l.range > 0.f) gl.range = nice(l.range);
  }
  if (l.kind == Light::Kind::spot) {
    gl.spot.innerConeAngle = double(radians(l.spot_inner_deg));
    gl.spot.outerConeAngle = double(radians(l.spot_outer_deg));
  }
  // The Scene's colour c = C I / pi (scene.h): I carries the pi.
  intensity *= pi;
  gl.color = nice_vector({color.r, color.g, color.b});
  gl.intensity = nice(intensity);
  Value::Object ex;
  ex["name"] = Value(l.name);
  ex["color"] = vec_value(l.color);
  ex["falloff"] = num(l.falloff);
  if (l.attenuation_constant != 0.f) ex["attenuation_constant"] = num(l.attenuation_constant);
  ex["position"] = vec_value(l.position);
  ex["direction"] = vec_value(l.direction);
  gl.extras = rayform_extras(std::move(ex));
  model_.lights.push_back(std::move(gl));
  tinygltf::Node n;
  n.name = model_.lights.back().name;
  n.extensions["KHR_lights_punctual"] = Value(Value::Object{{"light", Value(int(model_.lights.size()) - 1)}});
  if (l.kind != Light::Kind::directional) n.translation = nice_vector({l.position.x, l.position.y, l.position.z});
  if (l.kind != Light::Kind::point && glm::length(l.direction) > 0.f)
    n.rotation = quaternion(look_basis(l.direction, vec3(0.f, 1.f, 0.f)));
  return add_node(std::move(n));
}

Value GltfWriter::scene_extras() {
  const Background& b = scene_.background;
  Value::Object bg;
  bg["color"] = vec_value(b.color);
  bg["ambient"] = vec_value(b.ambient);
  if (b.cube_map[0] != invalid) {
    Value::Array faces;
    for (int f : b.cube_map) faces.push_back(Value(add_texture(f)));
    bg["cube_map"] = Value(std::move(faces));
    bg["cube_map_dir"] = Value(b.cube_map_dir);
  }
  return rayform_extras({{"version", Value(1)}, {"background", Value(std::move(bg))}});
}

}  // namespace rayform::gltf_detail
