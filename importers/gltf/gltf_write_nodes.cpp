// The glTF writer's node tree (GltfWriter, gltf_writer_internal.h): one glTF node
// per group or transform node, leading shape children gathered as its mesh;
// a matrix that one glTF node cannot hold (a shear) split into two that can.
#include "rayform/importers/gltf/gltf_writer_internal.h"
#include "rayform/base/error.h"

#include <algorithm>
#include <cmath>

namespace rayform::gltf_detail {

namespace {

// Whether a glTF node can hold m as a matrix: affine, and its linear part a
// rotation times a (possibly negative) scale: orthogonal columns.
bool is_trs(const mat4& m) {
  if (m[0][3] != 0.f || m[1][3] != 0.f || m[2][3] != 0.f || m[3][3] != 1.f) return false;
  vec3 c[3] = {vec3(m[0]), vec3(m[1]), vec3(m[2])};
  for (int i = 0; i < 3; ++i)
    for (int j = i + 1; j < 3; ++j) {
      float li = glm::length(c[i]), lj = glm::length(c[j]);
      if (std::abs(glm::dot(c[i], c[j])) > 1e-6f * li * lj) return false;
    }
  return true;
}

// Eigen-decomposition of a symmetric 3x3 matrix by Jacobi rotations (double):
// a = v diag(e) v^T, eigenvectors in v's columns.
void symmetric_eigen(glm::dmat3 a, glm::dmat3* v, glm::dvec3* e) {
  glm::dmat3 r(1.0);
  for (int sweep = 0; sweep < 50; ++sweep) {
    double off = a[0][1] * a[0][1] + a[0][2] * a[0][2] + a[1][2] * a[1][2];
    if (off < 1e-30) break;
    for (int p = 0; p < 2; ++p)
      for (int q = p + 1; q < 3; ++q) {
        if (std::abs(a[p][q]) < 1e-300) continue;
        double theta = (a[q][q] - a[p][p]) / (2.0 * a[p][q]);
        double t = (theta >= 0 ? 1.0 : -1.0) / (std::abs(theta) + std::sqrt(theta * theta + 1.0));
        double c = 1.0 / std::sqrt(t * t + 1.0), s = t * c;
        glm::dmat3 j(1.0);
        j[p][p] = c;
        j[q][q] = c;
        j[q][p] = s;   // column q, row p
        j[p][q] = -s;  // column p, row q
        a = glm::transpose(j) * a * j;
        r = r * j;
      }
  }
  *v = r;
  *e = glm::dvec3(a[0][0], a[1][1], a[2][2]);
}

// m = a * b with a = T R S and b = R' (both TRS): the singular value
// decomposition of the linear part, L = U S V^T, gives a = T U S and b = V^T.
void split_trs(const mat4& m, mat4* a, mat4* b) {
  const glm::dmat3 l = glm::dmat3(mat3(m));
  glm::dmat3 v;
  glm::dvec3 e;
  symmetric_eigen(glm::transpose(l) * l, &v, &e);
  if (glm::determinant(v) < 0) v[2] = -v[2];
  glm::dmat3 u;
  glm::dvec3 s;
  for (int i = 0; i < 3; ++i) {
    s[i] = std::sqrt(std::max(e[i], 0.0));
    u[i] = s[i] > 0 ? (l * v[i]) / s[i] : glm::dvec3(0.0);
  }
  // Re-orthonormalise U (Gram-Schmidt; a zero column is rebuilt by a cross product).
  u[0] = glm::length(u[0]) > 0 ? glm::normalize(u[0]) : glm::dvec3(1, 0, 0);
  u[1] = u[1] - glm::dot(u[1], u[0]) * u[0];
  u[1] = glm::length(u[1]) > 1e-12
             ? glm::normalize(u[1])
             : glm::normalize(glm::cross(u[0], std::abs(u[0].x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0)));
  glm::dvec3 c = glm::cross(u[0], u[1]);
  if (glm::dot(c, u[2]) < 0) s[2] = -s[2];  // a mirror: into the scale
  u[2] = c;
  glm::dmat3 us(u[0] * s[0], u[1] * s[1], u[2] * s[2]);
  *a = mat4(mat3(us));
  (*a)[3] = m[3];
  *b = mat4(mat3(glm::transpose(v)));
}

std::vector<double> matrix_values(const mat4& m) {
  std::vector<double> out;
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) out.push_back(nice(m[c][r]));
  return out;
}

}  // namespace

int GltfWriter::add_node(tinygltf::Node n) {
  model_.nodes.push_back(std::move(n));
  return int(model_.nodes.size()) - 1;
}

// Sets the node's transform: nothing for the identity, `matrix` when glTF
// can hold it, else a second node below (returned; -1 when not needed).
int GltfWriter::set_matrix(tinygltf::Node& n, const mat4& m) {
  if (is_identity(m)) return -1;
  if (is_trs(m)) {
    n.matrix = matrix_values(m);
    return -1;
  }
  mat4 a, b;
  split_trs(m, &a, &b);
  n.matrix = matrix_values(a);
  tinygltf::Node inner;
  inner.name = n.name + "#rotation";
  inner.matrix = matrix_values(b);
  ++sheared_;
  return add_node(std::move(inner));
}

// The nodes of the scene's top level.
std::vector<int> GltfWriter::root_nodes(const mat4& world) {
  const Node& root = scene_.nodes[size_t(scene_.root)];
  bool plain = root.kind == Node::Kind::group || (root.kind == Node::Kind::transform && is_identity(root.local));
  // Leading shapes need the root's own node (write_node gathers them).
  bool has_shapes = !root.children.empty() && root.children[0] >= 0 && size_t(root.children[0]) < scene_.nodes.size() &&
                    scene_.nodes[size_t(root.children[0])].kind == Node::Kind::shape &&
                    is_identity(scene_.nodes[size_t(root.children[0])].local) &&
                    scene_.nodes[size_t(root.children[0])].children.empty();
  if (plain && !has_shapes) {
    on_path_[size_t(scene_.root)] = 1;
    std::vector<int> out;
    for (int c : root.children) out.push_back(write_node(c, world));
    return out;
  }
  return {write_node(scene_.root, world)};
}

int GltfWriter::write_node(int index, const mat4& parent_world) {
  if (index < 0 || size_t(index) >= scene_.nodes.size())
    throw Error(context_.path + ": scene node " + std::to_string(index) + " does not exist");
  if (on_path_[size_t(index)])
    throw Error(context_.path + ": scene node " + std::to_string(index) + " is its own ancestor");
  on_path_[size_t(index)] = 1;
  const Node& n = scene_.nodes[size_t(index)];
  tinygltf::Node g;
  g.name = n.name;
  const mat4 world = n.kind == Node::Kind::group ? parent_world : parent_world * n.local;
  int inner = n.kind == Node::Kind::group ? -1 : set_matrix(g, n.local);
  std::vector<PrimitiveRef> shapes;
  std::vector<int> children;
  if (n.kind == Node::Kind::shape) {
    if (n.shape >= 0) shapes.push_back(PrimitiveRef{n.shape_kind, n.shape, n.material, world});
  }
  // The leading shapes become the node's mesh (a reader puts a node's mesh
  // before its children, so later shapes get nodes of their own to keep the order).
  bool leading = true;
  for (int c : n.children) {
    if (c >= 0 && size_t(c) < scene_.nodes.size()) {
      const Node& cn = scene_.nodes[size_t(c)];
      leading = leading && cn.kind == Node::Kind::shape && is_identity(cn.local) && cn.children.empty();
      if (leading) {
        if (cn.shape >= 0) shapes.push_back(PrimitiveRef{cn.shape_kind, cn.shape, cn.material, world});
        continue;
      }
    }
    children.push_back(write_node(c, world));
  }
  const int mesh = shapes.empty() ? -1 : add_mesh(shapes, n.name);
  if (inner >= 0) {
    // The shapes and children go below the second node of a split matrix.
    model_.nodes[size_t(inner)].mesh = mesh;
    model_.nodes[size_t(inner)].children = std::move(children);
    g.children = {inner};
  } else {
    g.mesh = mesh;
    g.children = std::move(children);
  }
  on_path_[size_t(index)] = 0;
  return add_node(std::move(g));
}

}  // namespace rayform::gltf_detail
