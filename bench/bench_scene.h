// A whole scene around one procedural mesh, for the render benchmarks and
// render_mesh_tool: the bumpy torus seen from above and in front, one
// directional and one point light, a Phong material.
#pragma once

#include "rayform/scene/procedural_mesh.h"
#include "rayform/scene/scene.h"

#include <utility>

namespace rayform::bench {

inline Scene make_mesh_scene(Mesh mesh) {
  Scene s;
  s.meshes.push_back(std::move(mesh));
  Material mat;
  mat.name = "clay";
  mat.diffuse = vec3(0.7f, 0.55f, 0.4f);
  mat.specular = vec3(0.3f);
  mat.shininess = 30.f;
  s.materials.push_back(mat);
  Camera cam;
  cam.name = "bench";
  cam.aspect = Camera::Aspect::fit;
  cam.center = vec3(0.f, 2.0f, 3.0f);
  cam.direction = -cam.center;
  cam.up = vec3(0.f, 1.f, 0.f);
  cam.fov_deg = 40.f;
  s.cameras.push_back(cam);
  Light sun;
  sun.kind = Light::Kind::directional;
  sun.direction = glm::normalize(vec3(-0.5f, -1.f, -0.3f));
  sun.color = vec3(0.8f);
  s.lights.push_back(sun);
  Light bulb;
  bulb.kind = Light::Kind::point;
  bulb.position = vec3(1.5f, 2.f, 2.f);
  bulb.color = vec3(0.4f);
  s.lights.push_back(bulb);
  s.background.color = vec3(0.1f, 0.2f, 0.4f);
  s.background.ambient = vec3(0.1f);
  Node root;
  root.name = "root";
  root.kind = Node::Kind::group;
  root.children = {1};
  Node shape;
  shape.name = "torus";
  shape.kind = Node::Kind::shape;
  shape.shape_kind = ShapeKind::mesh;
  shape.shape = 0;
  shape.material = 0;
  s.nodes = {root, shape};
  s.root = 0;
  return s;
}

}  // namespace rayform::bench
