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

}  // namespace rayform::test
