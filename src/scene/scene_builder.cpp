#include "rayform/scene/scene_builder.h"

#include "rayform/base/error.h"

#include <cmath>
#include <string>

namespace rayform {
namespace {

[[noreturn]] void fail(const char* call, const std::string& what) {
  throw Error(std::string("SceneBuilder::") + call + ": " + what);
}

std::string str(vec3 v) {
  std::string s(1, '(');  // not "(" + ...: GCC 12 warns falsely (-Wrestrict) on that
  s += std::to_string(v.x);
  s += ", ";
  s += std::to_string(v.y);
  s += ", ";
  s += std::to_string(v.z);
  s += ')';
  return s;
}

void check_finite(const char* call, const char* name, vec3 v) {
  if (!is_finite(v)) fail(call, std::string(name) + " must be finite, got " + str(v));
}

void check_colour(const char* call, const char* name, vec3 v) {
  check_finite(call, name, v);
  if (v.x < 0.f || v.y < 0.f || v.z < 0.f) fail(call, std::string(name) + " must not be negative, got " + str(v));
}

void check_non_negative(const char* call, const char* name, float v) {
  if (!(std::isfinite(v) && v >= 0.f))
    fail(call, std::string(name) + " must be a finite number >= 0, got " + std::to_string(v));
}

void check_texture(const char* call, const char* name, int handle, size_t textures) {
  if (handle != invalid && (handle < 0 || size_t(handle) >= textures))
    fail(call, std::string(name) + " " + std::to_string(handle) + " is not a texture handle (the scene has " +
                   std::to_string(textures) + " textures)");
}

}  // namespace

SceneBuilder::SceneBuilder() {
  Node root;
  root.name = "root";
  root.kind = Node::Kind::group;
  scene_.nodes.push_back(root);
  scene_.root = root_node;
  depth_.push_back(1);
}

int SceneBuilder::add_material(const Material& m) {
  const char* call = "add_material";
  check_colour(call, "diffuse", m.diffuse);
  check_colour(call, "specular", m.specular);
  check_colour(call, "emission", m.emission);
  check_non_negative(call, "shininess", m.shininess);
  check_non_negative(call, "refraction_index", m.refraction_index);
  if (!std::isfinite(m.alpha_cutoff)) fail(call, "alpha_cutoff must be finite");
  if (!std::isfinite(m.uv_transform.rotation) || !std::isfinite(m.uv_transform.offset.x) ||
      !std::isfinite(m.uv_transform.offset.y) || !std::isfinite(m.uv_transform.scale.x) ||
      !std::isfinite(m.uv_transform.scale.y))
    fail(call, "uv_transform must be finite");
  check_texture(call, "diffuse_texture", m.diffuse_texture, scene_.textures.size());
  check_texture(call, "bump_texture", m.bump_texture, scene_.textures.size());
  scene_.materials.push_back(m);
  return int(scene_.materials.size()) - 1;
}

SceneBuilder::Shape SceneBuilder::add_mesh(std::vector<vec3> positions, std::vector<uint32_t> indices,
                                           std::vector<vec3> normals, std::vector<vec2> uvs) {
  const char* call = "add_mesh";
  const size_t n = positions.size();
  if (n == 0) fail(call, "no positions");
  for (size_t i = 0; i < n; ++i)
    if (!is_finite(positions[i])) fail(call, "position " + std::to_string(i) + " is not finite: " + str(positions[i]));
  if (indices.empty() || indices.size() % 3 != 0)
    fail(call, "indices must be three per triangle, got " + std::to_string(indices.size()));
  for (size_t i = 0; i < indices.size(); ++i)
    if (indices[i] >= n)
      fail(call, "index " + std::to_string(i) + " (triangle " + std::to_string(i / 3) + ") is " +
                     std::to_string(indices[i]) + ", beyond the " + std::to_string(n) + " vertices");
  if (!normals.empty()) {
    if (normals.size() != n)
      fail(call, std::to_string(normals.size()) + " normals for " + std::to_string(n) + " positions");
    for (size_t i = 0; i < n; ++i)
      if (!is_finite(normals[i]) || normals[i] == vec3(0.f))
        fail(call, "normal " + std::to_string(i) + " must be finite and not zero, got " + str(normals[i]));
  }
  if (!uvs.empty()) {
    if (uvs.size() != n) fail(call, std::to_string(uvs.size()) + " uvs for " + std::to_string(n) + " positions");
    for (size_t i = 0; i < n; ++i)
      if (!std::isfinite(uvs[i].x) || !std::isfinite(uvs[i].y))
        fail(call, "uv " + std::to_string(i) + " is not finite");
  }
  Mesh mesh;
  mesh.name = "mesh" + std::to_string(scene_.meshes.size());
  mesh.positions = std::move(positions);
  mesh.indices = std::move(indices);
  mesh.normals = std::move(normals);
  mesh.uvs = std::move(uvs);
  scene_.meshes.push_back(std::move(mesh));
  return {ShapeKind::mesh, int(scene_.meshes.size()) - 1};
}

SceneBuilder::Shape SceneBuilder::add_sphere(vec3 center, float radius) {
  const char* call = "add_sphere";
  check_finite(call, "center", center);
  if (!(std::isfinite(radius) && radius > 0.f))
    fail(call, "radius must be a finite number > 0, got " + std::to_string(radius));
  scene_.spheres.push_back(Sphere{center, radius});
  return {ShapeKind::sphere, int(scene_.spheres.size()) - 1};
}

void SceneBuilder::check_parent(const char* call, int parent) const {
  if (parent < 0 || size_t(parent) >= scene_.nodes.size())
    fail(call, "parent " + std::to_string(parent) + " is not a node handle (the scene has " +
                   std::to_string(scene_.nodes.size()) + " nodes)");
  if (scene_.nodes[size_t(parent)].kind == Node::Kind::shape)
    fail(call, "parent " + std::to_string(parent) + " is an instance, which holds no children");
  if (depth_[size_t(parent)] >= max_node_depth)
    fail(call, "parent " + std::to_string(parent) + " is at the deepest level a tree may have (" +
                   std::to_string(max_node_depth) + ")");
}

int SceneBuilder::append_node(const Node& node, int parent) {
  scene_.nodes.push_back(node);
  const int handle = int(scene_.nodes.size()) - 1;
  scene_.nodes[size_t(parent)].children.push_back(handle);
  depth_.push_back(depth_[size_t(parent)] + 1);
  return handle;
}

int SceneBuilder::add_transform(const mat4& local, int parent) {
  const char* call = "add_transform";
  check_parent(call, parent);
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r)
      if (!std::isfinite(local[c][r])) fail(call, "the matrix must be finite");
  if (local[0][3] != 0.f || local[1][3] != 0.f || local[2][3] != 0.f || local[3][3] != 1.f)
    fail(call, "the matrix must be affine (last row 0 0 0 1)");
  const float det = glm::determinant(mat3(local));
  if (!(std::abs(det) > 0.f) || !std::isfinite(1.f / det)) fail(call, "the matrix must be invertible");
  Node n;
  n.kind = Node::Kind::transform;
  n.local = local;
  return append_node(n, parent);
}

int SceneBuilder::add_instance(Shape shape, int material, int parent) {
  const char* call = "add_instance";
  check_parent(call, parent);
  size_t count = 0;
  const char* kind = "";
  switch (shape.kind) {
    case ShapeKind::mesh: count = scene_.meshes.size(), kind = "mesh"; break;
    case ShapeKind::sphere: count = scene_.spheres.size(), kind = "sphere"; break;
    case ShapeKind::plane: count = scene_.planes.size(), kind = "plane"; break;
    case ShapeKind::triangle: count = scene_.triangles.size(), kind = "triangle"; break;
  }
  if (shape.index < 0 || size_t(shape.index) >= count)
    fail(call, "shape " + std::to_string(shape.index) + " is not a " + kind + " handle (the scene has " +
                   std::to_string(count) + ")");
  if (material != invalid && (material < 0 || size_t(material) >= scene_.materials.size()))
    fail(call, "material " + std::to_string(material) + " is not a material handle (the scene has " +
                   std::to_string(scene_.materials.size()) + ")");
  Node n;
  n.kind = Node::Kind::shape;
  n.shape_kind = shape.kind;
  n.shape = shape.index;
  n.material = material;
  return append_node(n, parent);
}

int SceneBuilder::add_camera(const Camera& c) {
  const char* call = "add_camera";
  check_finite(call, "center", c.center);
  check_finite(call, "direction", c.direction);
  check_finite(call, "up", c.up);
  if (c.direction == vec3(0.f)) fail(call, "direction must not be zero");
  if (!(glm::length(glm::cross(c.direction, c.up)) > 0.f)) fail(call, "up must not be zero or parallel to direction");
  if (c.projection == Camera::Projection::perspective && !(c.fov_deg > 0.f && c.fov_deg < 180.f))
    fail(call, "fov_deg must lie strictly between 0 and 180, got " + std::to_string(c.fov_deg));
  if (c.projection == Camera::Projection::orthographic && !(std::isfinite(c.ortho_height) && c.ortho_height > 0.f))
    fail(call, "ortho_height must be a finite number > 0, got " + std::to_string(c.ortho_height));
  scene_.cameras.push_back(c);
  return int(scene_.cameras.size()) - 1;
}

int SceneBuilder::add_light(const Light& l) {
  const char* call = "add_light";
  check_colour(call, "color", l.color);
  check_finite(call, "position", l.position);
  check_finite(call, "direction", l.direction);
  if (l.kind != Light::Kind::point && l.direction == vec3(0.f)) fail(call, "direction must not be zero");
  check_non_negative(call, "falloff", l.falloff);
  check_non_negative(call, "range", l.range);
  if (l.kind == Light::Kind::spot &&
      !(l.spot_inner_deg >= 0.f && l.spot_inner_deg <= l.spot_outer_deg && l.spot_outer_deg <= 90.f))
    fail(call, "spot angles must satisfy 0 <= inner <= outer <= 90, got " + std::to_string(l.spot_inner_deg) + " and " +
                   std::to_string(l.spot_outer_deg));
  scene_.lights.push_back(l);
  return int(scene_.lights.size()) - 1;
}

}  // namespace rayform
