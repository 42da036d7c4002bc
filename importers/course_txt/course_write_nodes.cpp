// The course writer's node tree (CourseWriter, course_writer_internal.h):
// nested Group / Transform blocks with MaterialIndex lines where the material
// changes; groups and identity transforms around a single object are left
// out, and so are groups that hold one group only.
#include "rayform/importers/course_txt/course_writer_internal.h"

#include "rayform/base/error.h"
#include "rayform/importers/text_format.h"

#include <set>
#include <sstream>

namespace rayform::course_detail {

// The parts a shape node is written as: (material, mesh part) pairs.
std::vector<std::pair<int, int>> CourseWriter::parts(const Node& n) const {
  if (n.shape < 0) return {};
  if (n.shape_kind == ShapeKind::mesh) {
    const Mesh& m = s_.meshes.at(size_t(n.shape));
    if (m.face_materials.size() == m.triangle_count() && !m.face_materials.empty()) {
      std::vector<std::pair<int, int>> out;
      std::set<int> seen;
      for (int fm : m.face_materials)
        if (seen.insert(fm).second) out.emplace_back(fm, fm);
      return out;
    }
  }
  return {{n.material, invalid}};
}

bool CourseWriter::group_like(const Node& n) const {
  return n.kind == Node::Kind::group || (n.kind == Node::Kind::transform && is_identity(n.local));
}

const Node& CourseWriter::node(int i) const {
  if (i < 0 || size_t(i) >= s_.nodes.size())
    throw Error(context_.path + ": scene node " + std::to_string(i) + " does not exist");
  return s_.nodes[size_t(i)];
}

int CourseWriter::children_objects(const Node& n) {
  int sum = 0;
  for (int c : n.children) sum += objects(c);
  return sum;
}

// How many course objects node i adds to the group that holds it.
int CourseWriter::objects(int i) {
  const Node& n = node(i);
  if (objects_.empty()) objects_.assign(s_.nodes.size(), -1);
  if (objects_[size_t(i)] >= 0) return objects_[size_t(i)];
  if (++depth_ > 10000) throw Error(context_.path + ": the node graph is too deep or has a cycle");
  int r;
  if (n.kind == Node::Kind::shape) {
    int p = int(parts(n).size());
    r = is_identity(n.local) ? p : (p > 0 ? 1 : 0);
  } else {
    r = children_objects(n) > 0 ? 1 : 0;
  }
  --depth_;
  objects_[size_t(i)] = r;
  return r;
}

// When node i is written as one shape (through groups and transforms that
// wrap it alone), the material of that shape.
bool CourseWriter::leaf_material(int i, int* material) {
  const Node& n = node(i);
  if (n.kind == Node::Kind::shape) {
    auto p = parts(n);
    if (p.size() != 1) return false;
    *material = p[0].first;
    return true;
  }
  if (children_objects(n) != 1) return false;
  for (int c : n.children)
    if (objects(c) > 0) return leaf_material(c, material);
  return false;
}

void CourseWriter::set_material(int m, std::ostringstream& o, const std::string& pad) {
  int k = m;
  if (m < 0 || size_t(m) >= s_.materials.size()) {
    if (current_ == -1) return;  // nothing set yet: the reader's "no material"
    need_default_ = true;
    k = int(s_.materials.size());
  }
  if (k == current_) return;
  o << pad << "MaterialIndex " << k << "\n";
  current_ = k;
}

std::string CourseWriter::matrix_text(const mat4& m) {
  std::string s = "Matrix4f {";
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) {
      s += ' ';
      s += format_float(m[c][r]);
    }
  return s + " }";
}

void CourseWriter::shape_text(const Node& n, int part, int material, std::ostringstream& o, const std::string& pad) {
  switch (n.shape_kind) {
    case ShapeKind::sphere: {
      const Sphere& s = s_.spheres.at(size_t(n.shape));
      o << pad << "Sphere {\n"
        << pad << "    center " << format_vec3(s.center) << "\n"
        << pad << "    radius " << format_float(s.radius) << "\n"
        << pad << "}\n";
      break;
    }
    case ShapeKind::plane: {
      const Plane& p = s_.planes.at(size_t(n.shape));
      o << pad << "Plane {\n"
        << pad << "    normal " << format_vec3(p.normal) << "\n"
        << pad << "    offset " << format_float(p.offset) << "\n"
        << pad << "}\n";
      break;
    }
    case ShapeKind::triangle: {
      const Triangle& t = s_.triangles.at(size_t(n.shape));
      o << pad << "Triangle {\n";
      for (int k = 0; k < 3; ++k) o << pad << "    vertex" << k << " " << format_vec3(t.vertices[size_t(k)]) << "\n";
      o << pad << "}\n";
      break;
    }
    case ShapeKind::mesh:
      o << pad << "TriangleMesh {\n"
        << pad << "    obj_file " << mesh_file(n.shape, part, material) << "\n"
        << pad << "}\n";
      break;
  }
}

// Writes node i's objects into the group body being written.
void CourseWriter::emit(int i, std::ostringstream& o, const std::string& pad) {
  const Node& n = node(i);
  if (objects(i) == 0) return;
  int leaf = invalid;
  if (leaf_material(i, &leaf)) set_material(leaf, o, pad);  // before any Transform around it
  if (n.kind == Node::Kind::shape) {
    auto p = parts(n);
    if (is_identity(n.local)) {
      for (auto [material, part] : p) {
        set_material(material, o, pad);
        shape_text(n, part, material, o, pad);
      }
      return;
    }
    o << pad << "Transform {\n" << pad << "    " << matrix_text(n.local) << "\n";
    if (p.size() == 1) {
      shape_text(n, p[0].second, p[0].first, o, pad + "    ");
    } else {
      o << pad << "    Group {\n" << pad << "        numObjects " << p.size() << "\n";
      for (auto [material, part] : p) {
        set_material(material, o, pad + "        ");
        shape_text(n, part, material, o, pad + "        ");
      }
      o << pad << "    }\n";
    }
    o << pad << "}\n";
    return;
  }
  const int sum = children_objects(n);
  if (group_like(n)) {
    if (sum == 1) {  // nothing to group: the one object alone
      for (int c : n.children) emit(c, o, pad);
      return;
    }
    write_group(n, sum, o, pad);
    return;
  }
  o << pad << "Transform {\n" << pad << "    " << matrix_text(n.local) << "\n";
  if (sum == 1) {
    for (int c : n.children) emit(c, o, pad + "    ");
  } else {
    write_group(n, sum, o, pad + "    ");
  }
  o << pad << "}\n";
}

void CourseWriter::write_group(const Node& n, int sum, std::ostringstream& o, const std::string& pad) {
  o << pad << "Group {\n" << pad << "    numObjects " << sum << "\n";
  for (int c : n.children) emit(c, o, pad + "    ");
  o << pad << "}\n";
}

std::string CourseWriter::top_group() {
  std::ostringstream o;
  int r = s_.root;
  // Groups that hold one group only are not written around it.
  for (;;) {
    const Node& n = node(r);
    if (!group_like(n) || children_objects(n) != 1) break;
    int only = invalid;
    for (int c : n.children)
      if (objects(c) > 0) only = c;
    if (only == invalid || !group_like(node(only)) || children_objects(node(only)) < 2) break;
    r = only;
  }
  const Node& n = node(r);
  if (group_like(n)) {
    int sum = children_objects(n);
    if (sum == 0) context_.note("the scene has no shapes: the Group is empty");
    write_group(n, sum, o, "");
  } else {
    o << "Group {\n    numObjects 1\n";
    emit(r, o, "    ");
    o << "}\n";
  }
  return o.str();
}

}  // namespace rayform::course_detail
