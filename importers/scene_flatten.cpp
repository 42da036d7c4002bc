#include "rayform/importers/scene_flatten.h"

#include "rayform/scene/node_walk.h"
#include "rayform/importers/shape_tessellation.h"

#include <cmath>
#include <map>
#include <utility>

namespace rayform {

namespace {

// Whether the linear part of m is a rotation times a uniform scale s (> 0).
bool is_similarity(const mat4& m, float* scale) {
  vec3 c0(m[0]), c1(m[1]), c2(m[2]);
  float l0 = glm::length(c0), l1 = glm::length(c1), l2 = glm::length(c2);
  float s = (l0 + l1 + l2) / 3.f;
  if (!(s > 0.f)) return false;
  const float tol = 1e-5f;
  if (std::abs(l0 - s) > tol * s || std::abs(l1 - s) > tol * s || std::abs(l2 - s) > tol * s) return false;
  if (std::abs(glm::dot(c0, c1)) > tol * s * s || std::abs(glm::dot(c1, c2)) > tol * s * s ||
      std::abs(glm::dot(c0, c2)) > tol * s * s)
    return false;
  *scale = s;
  return true;
}

}  // namespace

Mesh transform_mesh(const Mesh& src, const mat4& m) {
  Mesh out = src;
  const mat3 nm = glm::transpose(glm::inverse(mat3(m)));
  for (vec3& p : out.positions) p = transform_point(m, p);
  for (vec3& n : out.normals) {
    vec3 t = nm * n;
    float len = glm::length(t);
    n = len > 0.f ? t / len : vec3(0.f);
  }
  if (glm::determinant(mat3(m)) < 0.f)
    for (size_t i = 0; i + 2 < out.indices.size(); i += 3) std::swap(out.indices[i + 1], out.indices[i + 2]);
  return out;
}

Plane transform_plane(const Plane& p, const mat4& m) {
  vec3 nn = glm::normalize(p.normal);
  vec3 on = nn * (p.offset / glm::length(p.normal));
  vec3 wn = glm::normalize(glm::transpose(glm::inverse(mat3(m))) * nn);
  return Plane{wn, glm::dot(wn, transform_point(m, on))};
}

Scene flatten_scene(const Scene& scene, int sphere_segments, const std::string& name,
                    std::vector<std::string>* messages) {
  Scene out;
  out.source_path = scene.source_path;
  out.cameras = scene.cameras;
  out.lights = scene.lights;
  out.materials = scene.materials;
  out.textures = scene.textures;
  out.background = scene.background;
  Node root;
  root.kind = Node::Kind::group;
  root.name = scene.root != invalid ? scene.nodes[size_t(scene.root)].name : "root";
  std::vector<Node> shapes;
  std::map<int, int> shared_meshes;  // untransformed meshes keep one copy
  size_t tessellated = 0;
  for_each_shape_node(scene, [&](const Node& n, const mat4& m) {
    if (n.shape < 0) return;
    Node s;
    s.kind = Node::Kind::shape;
    s.name = n.name;
    s.material = n.material;
    s.shape_kind = n.shape_kind;
    switch (n.shape_kind) {
      case ShapeKind::sphere: {
        const Sphere& sp = scene.spheres.at(size_t(n.shape));
        float k = 1.f;
        if (is_similarity(m, &k)) {
          out.spheres.push_back(Sphere{transform_point(m, sp.center), sp.radius * k});
          s.shape = int(out.spheres.size()) - 1;
        } else {
          Mesh mesh = transform_mesh(tessellate_sphere(sp, sphere_segments), m);
          out.meshes.push_back(std::move(mesh));
          s.shape_kind = ShapeKind::mesh;
          s.shape = int(out.meshes.size()) - 1;
          ++tessellated;
        }
        break;
      }
      case ShapeKind::plane: {
        out.planes.push_back(is_identity(m) ? scene.planes.at(size_t(n.shape))
                                            : transform_plane(scene.planes.at(size_t(n.shape)), m));
        s.shape = int(out.planes.size()) - 1;
        break;
      }
      case ShapeKind::triangle: {
        Triangle t = scene.triangles.at(size_t(n.shape));
        for (vec3& v : t.vertices) v = transform_point(m, v);
        if (glm::determinant(mat3(m)) < 0.f) std::swap(t.vertices[1], t.vertices[2]);
        out.triangles.push_back(t);
        s.shape = int(out.triangles.size()) - 1;
        break;
      }
      case ShapeKind::mesh: {
        if (is_identity(m)) {
          auto it = shared_meshes.find(n.shape);
          if (it == shared_meshes.end()) {
            out.meshes.push_back(scene.meshes.at(size_t(n.shape)));
            it = shared_meshes.emplace(n.shape, int(out.meshes.size()) - 1).first;
          }
          s.shape = it->second;
        } else {
          out.meshes.push_back(transform_mesh(scene.meshes.at(size_t(n.shape)), m));
          s.shape = int(out.meshes.size()) - 1;
        }
        break;
      }
    }
    shapes.push_back(std::move(s));
  });
  for (Node& s : shapes) {
    out.nodes.push_back(std::move(s));
    root.children.push_back(int(out.nodes.size()) - 1);
  }
  out.nodes.push_back(std::move(root));
  out.root = int(out.nodes.size()) - 1;
  if (tessellated && messages)
    messages->push_back(name + ": --flatten: " + std::to_string(tessellated) +
                        " sphere(s) under a non-uniform scale or shear became triangle meshes (" +
                        std::to_string(sphere_segments) + " segments)");
  return out;
}

}  // namespace rayform
