// Scene nodes for tests built by hand.
#pragma once

#include "rayform/scene/scene.h"

#include <utility>
#include <vector>

namespace rayform::test {

// A shape node: shape `shape` of the array of `kind`, with `material`
// (invalid: the default material).
inline Node shape_node(ShapeKind kind, int shape, int material = invalid) {
  Node n;
  n.kind = Node::Kind::shape;
  n.shape_kind = kind;
  n.shape = shape;
  n.material = material;
  return n;
}

// Makes node 0 of `s` (which has no nodes yet) the root, a group holding
// `children`, which are appended after it in order.
inline void add_root_group(Scene& s, std::vector<Node> children) {
  s.nodes.push_back(Node{});
  s.root = 0;
  for (Node& n : children) {
    s.nodes.push_back(std::move(n));
    s.nodes[0].children.push_back(int(s.nodes.size()) - 1);
  }
}

// A lit sphere of radius 1.5 at the origin seen from z = 10 (30 degrees):
// about half the picture's width across, the corners `background`.
inline Scene lit_sphere_scene(vec3 background) {
  Scene s;
  Camera c;
  c.center = vec3(0.f, 0.f, 10.f);
  c.direction = vec3(0.f, 0.f, -1.f);
  c.fov_deg = 30.f;
  s.cameras.push_back(c);
  Light l;
  l.kind = Light::Kind::directional;
  l.direction = vec3(-0.3f, -0.5f, -1.f);
  l.color = vec3(0.9f);
  s.lights.push_back(l);
  s.background.color = background;
  Material m;
  m.diffuse = vec3(0.8f, 0.3f, 0.2f);
  s.materials = {m};
  s.spheres = {Sphere{vec3(0.f), 1.5f}};
  add_root_group(s, {shape_node(ShapeKind::sphere, 0, 0)});
  return s;
}

}  // namespace rayform::test
