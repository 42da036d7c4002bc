// The glTF reader's node graph (GltfReader, gltf_reader_internal.h): the
// scene's root nodes, the checks that the graph is a forest of trees, node
// transforms (matrix or T R S), the walk that turns nodes into Scene nodes
// (meshes, EXT_mesh_gpu_instancing, cameras and lights placed), and world
// matrices for skins.
#include "rayform/importers/gltf/gltf_reader_internal.h"

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>

#include <algorithm>
#include <cmath>

namespace rayform::gltf_detail {

// The nodes to start from, with how the file names them.
std::vector<std::pair<int, std::string>> GltfReader::root_nodes() {
  std::vector<std::pair<int, std::string>> out;
  int s = options_.scene >= 0 ? options_.scene : model_.defaultScene;
  if (options_.scene >= 0 && size_t(options_.scene) >= model_.scenes.size())
    fail("scene " + std::to_string(options_.scene) + " was asked for but the file has " +
         std::to_string(model_.scenes.size()) + " scenes");
  if (s < 0 && !model_.scenes.empty()) s = 0;
  if (s >= int(model_.scenes.size()))
    fail("scene: scene " + std::to_string(s) + " does not exist (the file has " + std::to_string(model_.scenes.size()) +
         " scenes)");
  if (s >= 0) {
    const tinygltf::Scene& sc = model_.scenes[size_t(s)];
    for (size_t k = 0; k < sc.nodes.size(); ++k)
      out.emplace_back(sc.nodes[k], idx("scenes", s) + "." + idx("nodes", long(k)));
    return out;
  }
  // No scenes at all: every node no other node names as a child.
  if (!model_.nodes.empty()) warn("the file has no scenes: drawing every node that has no parent");
  std::vector<uint8_t> is_child(model_.nodes.size(), 0);
  for (const tinygltf::Node& n : model_.nodes)
    for (int c : n.children)
      if (c >= 0 && size_t(c) < is_child.size()) is_child[size_t(c)] = 1;
  for (size_t i = 0; i < model_.nodes.size(); ++i)
    if (!is_child[i]) out.emplace_back(int(i), idx("nodes", long(i)));
  if (out.empty() && !model_.nodes.empty()) fail("nodes: every node is some node's child: the node graph is recursive");
  return out;
}

// A node that is its own ancestor, found by one depth-first pass over the
// graph from the roots, then from every node (an explicit stack: the graph
// may be thousands of levels deep; convert_node refuses those).
void GltfReader::check_no_cycle(const std::vector<std::pair<int, std::string>>& roots) {
  enum : uint8_t { unseen, open, done };
  std::vector<uint8_t> state(model_.nodes.size(), unseen);
  std::vector<std::pair<int, size_t>> stack;  // node, next child to visit
  auto visit = [&](int start) {
    if (start < 0 || size_t(start) >= state.size() || state[size_t(start)] != unseen) return;
    state[size_t(start)] = open;
    stack.emplace_back(start, 0);
    while (!stack.empty()) {
      auto& [node, next] = stack.back();
      const std::vector<int>& children = model_.nodes[size_t(node)].children;
      if (next == children.size()) {
        state[size_t(node)] = done;
        stack.pop_back();
        continue;
      }
      const size_t k = next++;
      const int c = children[k];
      if (c < 0 || size_t(c) >= state.size()) continue;  // convert_node names the bad index
      if (state[size_t(c)] == open)
        fail(idx("nodes", node) + "." + idx("children", long(k)) + ": " + idx("nodes", c) +
             " is its own ancestor (recursive node graph)");
      if (state[size_t(c)] == unseen) {
        state[size_t(c)] = open;
        stack.emplace_back(c, 0);
      }
    }
  };
  for (const auto& root : roots) visit(root.first);
  for (size_t i = 0; i < model_.nodes.size(); ++i) visit(int(i));
}

// glTF node hierarchies are disjoint trees (the specification): no node has
// two parents, and a scene lists root nodes, each once. A file that breaks
// this is refused: drawing each path through a shared node would multiply
// the shapes (40 levels of two parents: 2^40 of them).
void GltfReader::check_node_trees(const std::vector<std::pair<int, std::string>>& roots) {
  check_no_cycle(roots);
  std::vector<int> parent(model_.nodes.size(), invalid);
  for (size_t p = 0; p < model_.nodes.size(); ++p)
    for (int c : model_.nodes[p].children) {
      if (c < 0 || size_t(c) >= parent.size()) continue;  // convert_node names the bad index
      if (parent[size_t(c)] != invalid && parent[size_t(c)] != int(p))
        fail(idx("nodes", c) + ": has two parents, " + idx("nodes", parent[size_t(c)]) + " and " +
             idx("nodes", long(p)) + " (a glTF node hierarchy must be a tree)");
      if (parent[size_t(c)] == int(p)) fail(idx("nodes", long(p)) + ".children: names " + idx("nodes", c) + " twice");
      parent[size_t(c)] = int(p);
    }
  std::vector<uint8_t> listed(model_.nodes.size(), 0);
  for (const auto& [node, ref] : roots) {
    if (node < 0 || size_t(node) >= parent.size()) continue;
    if (parent[size_t(node)] != invalid)
      fail(ref + ": " + idx("nodes", node) + " is a child of " + idx("nodes", parent[size_t(node)]) +
           " (a scene lists root nodes only)");
    if (listed[size_t(node)]++) fail(ref + ": " + idx("nodes", node) + " is listed twice");
  }
}

mat4 GltfReader::node_matrix(const tinygltf::Node& n, const std::string& where) {
  auto check = [&](const std::vector<double>& v, size_t want, const char* name) {
    if (!v.empty() && v.size() != want)
      fail(where + "." + name + ": expected " + std::to_string(want) + " numbers, found " + std::to_string(v.size()));
    for (double d : v)
      if (!std::isfinite(d)) fail(where + "." + name + ": not a finite number");
  };
  check(n.matrix, 16, "matrix");
  if (!n.matrix.empty()) {
    mat4 m;
    for (int c = 0; c < 4; ++c)
      for (int r = 0; r < 4; ++r) m[c][r] = float(n.matrix[size_t(4 * c + r)]);  // column-major, as glm
    return m;
  }
  check(n.translation, 3, "translation");
  check(n.rotation, 4, "rotation");
  check(n.scale, 3, "scale");
  mat4 m(1.f);
  if (!n.translation.empty()) m = glm::translate(m, vec3(n.translation[0], n.translation[1], n.translation[2]));
  if (!n.rotation.empty()) {
    glm::quat q(float(n.rotation[3]), float(n.rotation[0]), float(n.rotation[1]),
                float(n.rotation[2]));  // w, x, y, z
    float len = glm::length(q);
    if (!(len > 0.f)) fail(where + ".rotation: the quaternion is zero");
    m = m * glm::mat4_cast(q / len);
  }
  if (!n.scale.empty()) m = glm::scale(m, vec3(n.scale[0], n.scale[1], n.scale[2]));
  return m;
}

int GltfReader::add_node(Node n) {
  scene_.nodes.push_back(std::move(n));
  return int(scene_.nodes.size()) - 1;
}

// `ref` is how the parent names the node, e.g. "nodes[0].children[2]".
// `depth` is the node's depth in the Scene (the root group is 1); its mesh
// primitives become shape nodes one level deeper, within max_node_depth.
int GltfReader::convert_node(int i, const std::string& ref, const mat4& parent_world, int depth) {
  if (depth + 1 > max_node_depth)
    fail(ref + ": the node hierarchy is too deep (a scene holds at most " + std::to_string(max_node_depth) +
         " levels)");
  if (i < 0 || size_t(i) >= model_.nodes.size())
    fail(ref + ": node " + std::to_string(i) + " does not exist (the file has " + std::to_string(model_.nodes.size()) +
         " nodes)");
  const std::string where = idx("nodes", i);
  if (on_path_[size_t(i)]) fail(ref + ": " + where + " is its own ancestor (recursive node graph)");
  if (nodes_[size_t(i)] != invalid) fail(ref + ": " + where + " is reached twice");  // check_node_trees refused it
  on_path_[size_t(i)] = 1;
  const tinygltf::Node& n = model_.nodes[size_t(i)];
  Node out;
  out.kind = Node::Kind::transform;
  out.name = n.name.empty() ? where : n.name;
  out.local = node_matrix(n, where);
  const mat4 world = parent_world * out.local;

  if (n.mesh != -1) {
    if (n.mesh < 0 || size_t(n.mesh) >= model_.meshes.size())
      fail(where + ".mesh: mesh " + std::to_string(n.mesh) + " does not exist (the file has " +
           std::to_string(model_.meshes.size()) + " meshes)");
    const tinygltf::Mesh& gm = model_.meshes[size_t(n.mesh)];
    // Morph weights: the node's, else the mesh's, else 0.
    std::vector<float> weights;
    for (double w : n.weights.empty() ? gm.weights : n.weights) {
      if (!std::isfinite(w))
        fail(where + (n.weights.empty() ? idx(".meshes", n.mesh) : std::string()) + ".weights: not finite");
      weights.push_back(float(w));
    }
    if (std::all_of(weights.begin(), weights.end(), [](float w) { return w == 0.f; })) weights.clear();
    if (n.skin != -1) {
      // A skinned mesh is posed by its joints alone, in world space; the
      // node's own transform does not apply to it (the specification).
      const std::vector<int>& shapes = mesh_shapes(n.mesh, weights, i);
      world_space_shapes_.insert(world_space_shapes_.end(), shapes.begin(), shapes.end());
    } else if (auto inst = n.extensions.find("EXT_mesh_gpu_instancing"); inst != n.extensions.end()) {
      for (const mat4& m : instance_matrices(inst->second, where + ".extensions.EXT_mesh_gpu_instancing")) {
        Node copy;
        copy.kind = Node::Kind::transform;
        copy.local = m;
        copy.children = mesh_shapes(n.mesh, weights, invalid);  // one mesh, shared by every instance
        out.children.push_back(add_node(std::move(copy)));
      }
      use_extension("EXT_mesh_gpu_instancing");
    } else {
      const std::vector<int>& shapes = mesh_shapes(n.mesh, weights, invalid);
      out.children.insert(out.children.end(), shapes.begin(), shapes.end());
    }
  }
  if (n.camera != -1) place_camera(n.camera, where, world);
  auto lit = n.extensions.find("KHR_lights_punctual");
  if (lit != n.extensions.end()) {
    const tinygltf::Value& v = lit->second;
    if (!v.IsObject() || !v.Has("light") || !v.Get("light").IsNumber())
      fail(where + ".extensions.KHR_lights_punctual: expected an object with a \"light\" index");
    place_light(v.Get("light").GetNumberAsInt(), where, world);
  }
  for (size_t k = 0; k < n.children.size(); ++k)
    out.children.push_back(convert_node(n.children[k], where + "." + idx("children", long(k)), world, depth + 1));
  on_path_[size_t(i)] = 0;
  int index = add_node(std::move(out));
  nodes_[size_t(i)] = index;
  return index;
}

// EXT_mesh_gpu_instancing: one matrix T R S per instance (each of the three
// optional), applied before the node's transform.
std::vector<mat4> GltfReader::instance_matrices(const tinygltf::Value& e, const std::string& ew) {
  if (!e.IsObject() || !e.Has("attributes") || !e.Get("attributes").IsObject())
    fail(ew + ": expected an object with \"attributes\"");
  const tinygltf::Value& attributes = e.Get("attributes");
  struct Attr {
    const char* name;
    int type;
    uint32_t formats;
    GltfAccessors::Floats values;
    bool present = false;
  };
  Attr attrs[] = {{"TRANSLATION", TINYGLTF_TYPE_VEC3, format_float, {}},
                  {"ROTATION", TINYGLTF_TYPE_VEC4, formats_rotation, {}},
                  {"SCALE", TINYGLTF_TYPE_VEC3, format_float, {}}};
  size_t count = 0;
  const char* first = nullptr;
  for (Attr& a : attrs) {
    if (!attributes.Has(a.name)) continue;
    const std::string aw = ew + ".attributes." + a.name;
    const tinygltf::Value& index = attributes.Get(a.name);
    if (!index.IsNumber()) fail(aw + ": expected an accessor index");
    // Counted against the limit before any matrix is built.
    const size_t declared = accessors_.accessor(index.GetNumberAsInt(), aw).count;
    if (!fits_in(instances_, declared, options_.limits.instances))
      fail(aw + ": " + std::to_string(declared) + " instances: " +
           limit_exceeded("instances", declared > UINT64_MAX - instances_ ? UINT64_MAX : instances_ + declared,
                          options_.limits.instances));
    a.values = accessors_.read_floats(index.GetNumberAsInt(), aw, {a.type}, a.formats);
    a.present = true;
    for (float v : a.values.values)
      if (!std::isfinite(v)) fail(aw + ": a value is not finite");
    if (first && a.values.count != count)
      fail(aw + ": " + std::to_string(a.values.count) + " instances, but " + first + " has " + std::to_string(count));
    count = a.values.count;
    first = a.name;
  }
  if (!first) fail(ew + ".attributes: expected TRANSLATION, ROTATION or SCALE");
  instances_ += count;
  std::vector<mat4> out(count, mat4(1.f));
  for (size_t i = 0; i < count; ++i) {
    mat4& m = out[i];
    if (attrs[0].present)
      m = glm::translate(
          m, vec3(attrs[0].values.values[3 * i], attrs[0].values.values[3 * i + 1], attrs[0].values.values[3 * i + 2]));
    if (attrs[1].present) {
      const float* q = &attrs[1].values.values[4 * i];
      glm::quat r(q[3], q[0], q[1], q[2]);  // w, x, y, z
      const float len = glm::length(r);
      if (!(len > 0.f)) fail(ew + ".attributes.ROTATION: instance " + std::to_string(i) + "'s quaternion is zero");
      m = m * glm::mat4_cast(r / len);
    }
    if (attrs[2].present)
      m = glm::scale(
          m, vec3(attrs[2].values.values[3 * i], attrs[2].values.values[3 * i + 1], attrs[2].values.values[3 * i + 2]));
  }
  return out;
}

// Node i's world matrix through its (first) parents, whether or not it is in
// the scene read; joints of skins need it.
mat4 GltfReader::node_world(int i) {
  if (parents_.empty()) {
    parents_.assign(model_.nodes.size(), invalid);
    for (size_t p = 0; p < model_.nodes.size(); ++p)
      for (int c : model_.nodes[p].children)
        if (c >= 0 && size_t(c) < parents_.size() && parents_[size_t(c)] == invalid) parents_[size_t(c)] = int(p);
  }
  mat4 world(1.f);
  int depth = 0;
  for (int k = i; k != invalid; k = parents_[size_t(k)]) {
    if (++depth > max_node_depth)
      fail(idx("nodes", i) + ": its chain of parents is longer than " + std::to_string(max_node_depth) +
           " (recursive node graph?)");
    world = node_matrix(model_.nodes[size_t(k)], idx("nodes", k)) * world;
  }
  return world;
}

}  // namespace rayform::gltf_detail
