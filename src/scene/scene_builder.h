// Building a Scene in code: materials, meshes, spheres, transform nodes and
// instances of shapes under them, cameras and lights, each added by one call
// that returns an integer handle (an index into the Scene's arrays) and
// checks its arguments once, so that the scene it builds always prepares.
// A bad argument (a handle out of range, an index beyond the vertex count, a
// non-finite number, ...) is a rayform::Error naming the call and what was
// wrong, and leaves the scene as it was.
//
//   SceneBuilder b;
//   Material m;
//   m.diffuse = vec3(0.8f, 0.1f, 0.1f);
//   int red = b.add_material(m);
//   SceneBuilder::Shape ball = b.add_sphere(vec3(0.f), 1.f);
//   int moved = b.add_transform(glm::translate(mat4(1.f), vec3(2.f, 0.f, 0.f)));
//   b.add_instance(ball, red);         // at the origin
//   b.add_instance(ball, red, moved);  // and at (2, 0, 0)
//   Scene scene = b.take();            // add a camera and lights first, or use scene_defaults.h
#pragma once

#include "rayform/scene/scene.h"

#include <cstdint>
#include <vector>

namespace rayform {

class SceneBuilder {
 public:
  // A shape to instance: the array it lives in and its index there.
  struct Shape {
    ShapeKind kind = ShapeKind::mesh;
    int index = invalid;
  };

  // An empty scene whose root is a group node (handle root()).
  SceneBuilder();

  // Colours finite and >= 0, shininess finite and >= 0, refraction index
  // finite and >= 0, alpha cut-off finite, texture handles invalid or of the
  // scene's textures. Returns the material's handle.
  int add_material(const Material& material);

  // A triangle mesh: positions (at least one, finite), three indices per
  // triangle (each below the number of positions), and optionally one
  // normal (finite, not zero) and one uv (finite) per position.
  Shape add_mesh(std::vector<vec3> positions, std::vector<uint32_t> indices, std::vector<vec3> normals = {},
                 std::vector<vec2> uvs = {});

  // A sphere: finite centre, finite radius > 0.
  Shape add_sphere(vec3 center, float radius);

  // A transform node under `parent` (a group or transform node): `local`
  // maps its children's coordinates to the parent's; finite, affine (last
  // row 0 0 0 1) and invertible. Returns the node's handle.
  int add_transform(const mat4& local, int parent = root_node);

  // An instance of `shape` under `parent`, with `material` (a material
  // handle, or invalid: the default material). Returns the node's handle.
  int add_instance(Shape shape, int material = invalid, int parent = root_node);

  // A camera: finite centre, finite non-zero direction, up finite and not
  // parallel to it, 0 < fov_deg < 180 (perspective) or ortho_height > 0
  // (orthographic). Returns the camera's handle (RenderOptions::camera).
  int add_camera(const Camera& camera);

  // A light: finite position, colour finite and >= 0, direction finite and
  // not zero (directional, spot), falloff and range finite and >= 0, spot
  // angles finite with 0 <= inner <= outer <= 90. Returns the light's handle.
  int add_light(const Light& light);

  static constexpr int root_node = 0;
  const Scene& scene() const { return scene_; }
  // The scene built; the builder is left empty (call no more adds).
  Scene take() { return std::move(scene_); }

 private:
  Scene scene_;
  std::vector<int> depth_;  // per node: its depth in the tree (root = 1)
  void check_parent(const char* call, int parent) const;
  // Adds `node` as the last child of `parent` (checked already); returns its handle.
  int append_node(const Node& node, int parent);
};

}  // namespace rayform
