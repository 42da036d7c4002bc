#include "rayform/scene/node_walk.h"

#include <algorithm>

namespace rayform {
namespace {
constexpr uint64_t not_counted = ~uint64_t(0);

uint64_t count_visits(const Scene& scene, int index, int depth, uint64_t cap, std::vector<uint64_t>& counted,
                      std::vector<uint8_t>& on_path) {
  detail::check_visit(scene, index, depth, on_path);
  if (counted[size_t(index)] != not_counted) return counted[size_t(index)];
  on_path[size_t(index)] = 1;
  const Node& n = scene.nodes[size_t(index)];
  uint64_t visits = n.kind == Node::Kind::shape ? 1 : 0;
  for (int c : n.children)
    visits = std::min(cap + 1, visits + count_visits(scene, c, depth + 1, cap, counted, on_path));
  on_path[size_t(index)] = 0;
  counted[size_t(index)] = visits;
  return visits;
}
}  // namespace

void detail::check_visit(const Scene& scene, int index, int depth, const std::vector<uint8_t>& on_path) {
  if (depth > max_node_depth)
    throw Error("scene: the node hierarchy is too deep (a scene holds at most " + std::to_string(max_node_depth) +
                " levels)");
  if (index < 0 || index >= int(scene.nodes.size()))
    throw Error("scene: node index " + std::to_string(index) + " out of range");
  if (on_path[size_t(index)]) throw Error("scene: node " + std::to_string(index) + " is its own ancestor (cycle)");
}

uint64_t count_shape_visits(const Scene& scene, uint64_t cap) {
  if (scene.root == invalid) return 0;
  cap = std::min(cap, not_counted - 2);  // cap + 1 stays a count
  std::vector<uint64_t> counted(scene.nodes.size(), not_counted);
  std::vector<uint8_t> on_path(scene.nodes.size(), 0);
  return count_visits(scene, scene.root, 1, cap, counted, on_path);
}

}  // namespace rayform
