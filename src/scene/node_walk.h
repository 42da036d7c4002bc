// Walking the node tree: one callback per shape node with its object-to-world
// matrix (the product of the transforms above it). Shared by prepare,
// statistics and the writers. A node reachable from itself, a tree deeper
// than max_node_depth, or more paths to shapes than Limits::instances, is an
// error.
#pragma once

#include "rayform/base/error.h"
#include "rayform/base/limits.h"
#include "rayform/scene/scene.h"

#include <string>
#include <vector>

namespace rayform {

namespace detail {
// Refuses (rayform::Error) a visit of node `index` at `depth` (the root is 1)
// that is too deep, out of range, or on the path to itself.
void check_visit(const Scene& scene, int index, int depth, const std::vector<uint8_t>& on_path);

template <class Fn>
void walk_nodes(const Scene& scene, int index, const mat4& parent, int depth, std::vector<uint8_t>& on_path, Fn& fn) {
  check_visit(scene, index, depth, on_path);
  on_path[index] = 1;
  const Node& n = scene.nodes[index];
  mat4 m = n.kind == Node::Kind::group ? parent : parent * n.local;
  if (n.kind == Node::Kind::shape) fn(n, m);
  for (int c : n.children) walk_nodes(scene, c, m, depth + 1, on_path, fn);
  on_path[index] = 0;
}
}  // namespace detail

// How many shape nodes a walk from the root visits (a node that two parents
// name is visited once per path to it), counted without walking the paths:
// the number is at most `cap` + 1 (counting stops there), so a graph whose
// paths multiply (2^40 of them, say) is measured in time linear in its size.
uint64_t count_shape_visits(const Scene& scene, uint64_t cap);

// Calls fn(shape node, object-to-world matrix) for every path from the root to
// a shape node. Refuses (rayform::Error) a hierarchy whose paths number more
// than `max_instances` before walking any.
template <class Fn>
void for_each_shape_node(const Scene& scene, Fn&& fn, uint64_t max_instances = Limits{}.instances) {
  if (scene.root == invalid) return;
  if (count_shape_visits(scene, max_instances) > max_instances)
    throw Error("scene: the node hierarchy makes more than " + std::to_string(max_instances) +
                " shape instances (raise the limit with --limit instances=N)");
  std::vector<uint8_t> on_path(scene.nodes.size(), 0);
  detail::walk_nodes(scene, scene.root, mat4(1.f), 1, on_path, fn);
}

}  // namespace rayform
