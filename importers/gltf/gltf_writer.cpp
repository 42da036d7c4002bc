#include "gltf/gltf_writer.h"

#include "gltf/gltf_material.h"
#include "image/checked_write.h"
#include "image/output_files.h"
#include "scene_writer.h"
#include "shape_tessellation.h"
#include "text_format.h"
#include "texture_files.h"

#include "scene/error.h"
#include "scene/file_extension.h"
#include "scene/node_walk.h"

// Debian's tinygltf is a prebuilt library: never define TINYGLTF_IMPLEMENTATION here.
#include <nlohmann/json.hpp>
#include <tiny_gltf.h>

#include <glm/gtc/quaternion.hpp>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <tuple>

namespace rayform {
namespace fs = std::filesystem;

namespace {

using Value = tinygltf::Value;

// ---- JSON values ---------------------------------------------------------------------

// The float as the double of its shortest decimal text (0.9f -> 0.9), so that
// the JSON reads well and still gives back the same float.
double nice(float f) {
  double d = std::strtod(format_float(f).c_str(), nullptr);
  return float(d) == f ? d : double(f);
}

Value num(float f) { return Value(nice(f)); }
Value vec_value(vec3 v) { return Value(Value::Array{num(v.x), num(v.y), num(v.z)}); }

std::vector<double> nice_vector(std::initializer_list<float> fs) {
  std::vector<double> out;
  for (float f : fs) out.push_back(nice(f));
  return out;
}

// extras = { "rayform": obj }
Value rayform_extras(Value::Object obj) {
  Value::Object root;
  root["rayform"] = Value(std::move(obj));
  return Value(std::move(root));
}

// ---- matrices ----------------------------------------------------------------------------

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

// Rotation (x, y, z, w) of a right-handed orthonormal basis (columns).
std::vector<double> quaternion(const mat3& basis) {
  glm::dquat q = glm::quat_cast(glm::dmat3(basis));
  q = glm::normalize(q);
  return {q.x, q.y, q.z, q.w};
}

// A basis whose -z axis is `dir` (and whose y axis is as close to `up` as can be).
mat3 look_basis(vec3 dir, vec3 up) {
  vec3 w = glm::normalize(dir);
  vec3 u = glm::cross(w, up);
  if (!(glm::length(u) > 1e-6f)) u = glm::cross(w, std::abs(w.y) < 0.9f ? vec3(0, 1, 0) : vec3(1, 0, 0));
  u = glm::normalize(u);
  vec3 v = glm::cross(u, w);
  return mat3(u, v, -w);
}

// ---- the writer --------------------------------------------------------------------------

constexpr int array_buffer = TINYGLTF_TARGET_ARRAY_BUFFER;
constexpr int element_buffer = TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER;

// Keeps every image's URI as set here (tinygltf would otherwise re-encode).
bool keep_image_uri(const std::string*, const std::string*, const tinygltf::Image* image, bool, std::string* out_uri,
                    void*) {
  *out_uri = image->uri;
  return true;
}

// One primitive to write: a shape with its material (and, for planes, the
// object-to-world matrix that places the quad).
struct PrimitiveRef {
  ShapeKind kind;
  int shape;
  int material;
  mat4 world{1.f};
  bool operator<(const PrimitiveRef& o) const {
    return std::tie(kind, shape, material) < std::tie(o.kind, o.shape, o.material);
  }
};

class GltfBuilder {
 public:
  GltfBuilder(const Scene& scene, const std::string& path, const GltfWriteOptions& options,
              std::vector<std::string>* messages)
      : scene_(scene), path_(path), options_(options), messages_(messages), out_(path) {
    protect_scene_inputs(scene, out_);
    name_ = fs::path(path).filename().string();
    stem_ = fs::path(path).stem().string();
    extent_ = scene_extent(scene);
    if (!extent_.empty()) {
      extent_center_ = extent_.center();
      extent_radius_ = std::max(0.5f * glm::length(extent_.extent()), 1.f);
    }
  }

  SaveResult write() {
    model_.asset.version = "2.0";
    model_.asset.generator = "rayform convert";
    for (size_t i = 0; i < scene_.materials.size(); ++i) add_material(int(i));

    tinygltf::Scene gs;
    gs.name = scene_.nodes[size_t(scene_.root)].name;
    on_path_.assign(scene_.nodes.size(), 0);
    for (int n : root_nodes(mat4(1.f))) gs.nodes.push_back(n);
    for (size_t i = 0; i < scene_.cameras.size(); ++i) gs.nodes.push_back(add_camera(int(i)));
    for (size_t i = 0; i < scene_.lights.size(); ++i) gs.nodes.push_back(add_light(int(i)));
    gs.extras = scene_extras();
    model_.scenes.push_back(std::move(gs));
    model_.defaultScene = 0;
    report();
    return save();
  }

 private:
  void note(const std::string& m) {
    if (messages_) messages_->push_back(name_ + ": " + m);
  }

  // ---- buffers ----------------------------------------------------------------

  int add_view(const void* data, size_t bytes, int target) {
    while (buffer_.size() % 4) buffer_.push_back(0);
    tinygltf::BufferView v;
    v.buffer = 0;
    v.byteOffset = buffer_.size();
    v.byteLength = bytes;
    v.target = target;
    const uint8_t* b = static_cast<const uint8_t*>(data);
    buffer_.insert(buffer_.end(), b, b + bytes);
    model_.bufferViews.push_back(v);
    return int(model_.bufferViews.size()) - 1;
  }

  int add_accessor(int view, int component, size_t count, int type, std::vector<double> min = {},
                   std::vector<double> max = {}) {
    tinygltf::Accessor a;
    a.bufferView = view;
    a.byteOffset = 0;
    a.componentType = component;
    a.count = count;
    a.type = type;
    a.minValues = std::move(min);
    a.maxValues = std::move(max);
    model_.accessors.push_back(a);
    return int(model_.accessors.size()) - 1;
  }

  int add_vec3s(const std::vector<vec3>& v, bool bounds) {
    std::vector<double> lo, hi;
    if (bounds) {
      vec3 a(infinity), b(-infinity);
      for (const vec3& p : v) {
        a = glm::min(a, p);
        b = glm::max(b, p);
      }
      lo = {double(a.x), double(a.y), double(a.z)};
      hi = {double(b.x), double(b.y), double(b.z)};
    }
    int view = add_view(v.data(), v.size() * sizeof(vec3), array_buffer);
    return add_accessor(view, TINYGLTF_COMPONENT_TYPE_FLOAT, v.size(), TINYGLTF_TYPE_VEC3, lo, hi);
  }

  // ---- geometry -------------------------------------------------------------------

  struct Geometry {
    int position = -1, normal = -1, uv = -1, color = -1, indices = -1;
    size_t triangles = 0;
  };

  // The accessors of a mesh (restricted to the faces of one material when
  // `only_material` is not invalid and the mesh has face materials).
  Geometry mesh_geometry(const Mesh& m, int only_material) {
    std::vector<uint32_t> corners;
    if (only_material == invalid || m.face_materials.empty()) {
      corners = m.indices;
    } else {
      for (size_t f = 0; f < m.triangle_count(); ++f)
        if (m.face_materials[f] == only_material)
          corners.insert(corners.end(), m.indices.begin() + long(3 * f), m.indices.begin() + long(3 * f + 3));
    }
    // Only the vertices these faces use, in first-use order.
    std::vector<int64_t> remap(m.positions.size(), -1);
    std::vector<uint32_t> used;
    for (uint32_t& c : corners) {
      if (c >= m.positions.size()) throw Error(path_ + ": mesh '" + m.name + "' has an index out of range");
      if (remap[c] < 0) {
        remap[c] = int64_t(used.size());
        used.push_back(c);
      }
      c = uint32_t(remap[c]);
    }
    std::vector<vec3> pos, nor, col;
    std::vector<vec2> uv;
    for (uint32_t i : used) {
      pos.push_back(m.positions[i]);
      if (m.normals.size() == m.positions.size()) {
        vec3 n = m.normals[i];
        float len = glm::length(n);
        if (!(len > 0.f) || !std::isfinite(len)) {
          n = vec3(0.f, 0.f, 1.f);
          ++zero_normals_;
        } else if (std::abs(len - 1.f) > 1e-6f) {
          n /= len;  // unit normals are kept bit for bit
        }
        nor.push_back(n);
      }
      if (m.uvs.size() == m.positions.size()) uv.push_back(vec2(m.uvs[i].x, 1.f - m.uvs[i].y));
      if (m.colors.size() == m.positions.size()) col.push_back(m.colors[i]);
    }
    // Equal data (e.g. one mesh read back as a copy per material) is stored once.
    std::string key;
    auto append = [&key](const void* d, size_t n) {
      key.append(static_cast<const char*>(d), n);
      key += '|';
    };
    append(pos.data(), pos.size() * sizeof(vec3));
    append(nor.data(), nor.size() * sizeof(vec3));
    append(uv.data(), uv.size() * sizeof(vec2));
    append(col.data(), col.size() * sizeof(vec3));
    append(corners.data(), corners.size() * sizeof(uint32_t));
    if (auto it = stored_.find(key); it != stored_.end()) return it->second;
    Geometry g;
    g.triangles = corners.size() / 3;
    g.position = add_vec3s(pos, true);
    if (!nor.empty()) g.normal = add_vec3s(nor, false);
    if (!uv.empty()) {
      int view = add_view(uv.data(), uv.size() * sizeof(vec2), array_buffer);
      g.uv = add_accessor(view, TINYGLTF_COMPONENT_TYPE_FLOAT, uv.size(), TINYGLTF_TYPE_VEC2);
    }
    if (!col.empty()) g.color = add_vec3s(col, false);
    if (pos.size() < 65535) {  // 65535 is the restart value: not an index
      std::vector<uint16_t> i16(corners.begin(), corners.end());
      int view = add_view(i16.data(), i16.size() * 2, element_buffer);
      g.indices = add_accessor(view, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT, i16.size(), TINYGLTF_TYPE_SCALAR);
    } else {
      int view = add_view(corners.data(), corners.size() * 4, element_buffer);
      g.indices = add_accessor(view, TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT, corners.size(), TINYGLTF_TYPE_SCALAR);
    }
    stored_.emplace(std::move(key), g);
    return g;
  }

  tinygltf::Primitive primitive(const Geometry& g, int material) {
    tinygltf::Primitive p;
    p.mode = TINYGLTF_MODE_TRIANGLES;
    p.indices = g.indices;
    p.attributes["POSITION"] = g.position;
    if (g.normal >= 0) p.attributes["NORMAL"] = g.normal;
    if (g.uv >= 0) p.attributes["TEXCOORD_0"] = g.uv;
    if (g.color >= 0) p.attributes["COLOR_0"] = g.color;
    if (g.uv < 0 && material >= 0 &&
        model_.materials[size_t(material)].pbrMetallicRoughness.baseColorTexture.index >= 0)
      material = untextured(material);
    p.material = material;
    return p;
  }

  int gltf_material(int m) const {
    return m >= 0 && m < int(scene_.materials.size()) ? m : -1;  // -1: glTF's default material
  }

  // The primitives of one shape (several for a mesh with face materials).
  std::vector<tinygltf::Primitive> shape_primitives(const PrimitiveRef& r) {
    std::vector<tinygltf::Primitive> out;
    switch (r.kind) {
      case ShapeKind::sphere: {
        const Sphere& s = scene_.spheres.at(size_t(r.shape));
        auto it = sphere_geometry_.find(r.shape);
        if (it == sphere_geometry_.end())
          it = sphere_geometry_.emplace(r.shape, mesh_geometry(tessellate_sphere(s, options_.sphere_segments), invalid))
                   .first;
        tinygltf::Primitive p = primitive(it->second, gltf_material(r.material));
        if (options_.shape_extras)
          p.extras = rayform_extras(
              {{"sphere", Value(Value::Object{{"center", vec_value(s.center)}, {"radius", num(s.radius)}})}});
        out.push_back(std::move(p));
        ++spheres_;
        break;
      }
      case ShapeKind::plane: {
        const Plane& pl = scene_.planes.at(size_t(r.shape));
        // The quad around the scene's extent, seen in the plane's object space.
        vec3 around(0.f);
        float half = plane_quad_scale;
        if (!extent_.empty()) {
          mat4 inv = glm::inverse(r.world);
          Bounds3 local = transform_bounds(inv, extent_);
          around = local.center();
          half = plane_quad_scale * std::max(0.5f * glm::length(local.extent()), 1.f);
        }
        plane_half_ = std::max(plane_half_, half);
        Geometry g = mesh_geometry(plane_quad(pl, around, half), invalid);
        tinygltf::Primitive p = primitive(g, gltf_material(r.material));
        if (options_.shape_extras)
          p.extras = rayform_extras(
              {{"plane", Value(Value::Object{{"normal", vec_value(pl.normal)}, {"offset", num(pl.offset)}})}});
        out.push_back(std::move(p));
        ++planes_;
        break;
      }
      case ShapeKind::triangle: {
        const Triangle& t = scene_.triangles.at(size_t(r.shape));
        Mesh m;
        m.positions.assign(t.vertices.begin(), t.vertices.end());
        m.indices = {0, 1, 2};
        tinygltf::Primitive p = primitive(mesh_geometry(m, invalid), gltf_material(r.material));
        if (options_.shape_extras) p.extras = rayform_extras({{"triangle", Value(true)}});
        out.push_back(std::move(p));
        break;
      }
      case ShapeKind::mesh: {
        const Mesh& m = scene_.meshes.at(size_t(r.shape));
        std::vector<int> mats;
        if (m.face_materials.size() == m.triangle_count() && !m.face_materials.empty()) {
          std::set<int> seen;
          for (int fm : m.face_materials)
            if (seen.insert(fm).second) mats.push_back(fm);
        } else {
          mats.push_back(invalid);
        }
        for (int fm : mats) {
          auto key = std::make_pair(r.shape, fm);
          auto it = mesh_geometry_.find(key);
          if (it == mesh_geometry_.end()) it = mesh_geometry_.emplace(key, mesh_geometry(m, fm)).first;
          tinygltf::Primitive p = primitive(it->second, gltf_material(fm == invalid ? r.material : fm));
          if (!m.name.empty()) p.extras = rayform_extras({{"name", Value(m.name)}});
          out.push_back(std::move(p));
        }
        if (mats.size() > 1) ++split_meshes_;
        break;
      }
    }
    return out;
  }

  // One glTF mesh for a list of shapes, reused when the same list recurs
  // (planes are placed by their world matrix, so they are never shared).
  int add_mesh(const std::vector<PrimitiveRef>& refs, const std::string& name) {
    bool shareable =
        std::none_of(refs.begin(), refs.end(), [](const PrimitiveRef& r) { return r.kind == ShapeKind::plane; });
    if (shareable) {
      auto it = meshes_.find(refs);
      if (it != meshes_.end()) return it->second;
    }
    tinygltf::Mesh gm;
    gm.name = name;
    for (const PrimitiveRef& r : refs)
      for (tinygltf::Primitive& p : shape_primitives(r)) gm.primitives.push_back(std::move(p));
    model_.meshes.push_back(std::move(gm));
    int index = int(model_.meshes.size()) - 1;
    if (shareable) meshes_[refs] = index;
    return index;
  }

  // ---- nodes ----------------------------------------------------------------------

  int add_node(tinygltf::Node n) {
    model_.nodes.push_back(std::move(n));
    return int(model_.nodes.size()) - 1;
  }

  // Sets the node's transform: nothing for the identity, `matrix` when glTF
  // can hold it, else a second node below (returned; -1 when not needed).
  int set_matrix(tinygltf::Node& n, const mat4& m) {
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
  std::vector<int> root_nodes(const mat4& world) {
    const Node& root = scene_.nodes[size_t(scene_.root)];
    bool plain = root.kind == Node::Kind::group || (root.kind == Node::Kind::transform && is_identity(root.local));
    // Leading shapes need the root's own node (write_node gathers them).
    bool has_shapes = !root.children.empty() && root.children[0] >= 0 &&
                      size_t(root.children[0]) < scene_.nodes.size() &&
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

  int write_node(int index, const mat4& parent_world) {
    if (index < 0 || size_t(index) >= scene_.nodes.size())
      throw Error(path_ + ": scene node " + std::to_string(index) + " does not exist");
    if (on_path_[size_t(index)]) throw Error(path_ + ": scene node " + std::to_string(index) + " is its own ancestor");
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

  // ---- materials and textures ---------------------------------------------------------

  int add_sampler(const Texture& t) {
    auto wrap = [](Texture::Wrap w) {
      switch (w) {
        case Texture::Wrap::clamp: return TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE;
        case Texture::Wrap::mirror: return TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT;
        default: return TINYGLTF_TEXTURE_WRAP_REPEAT;
      }
    };
    tinygltf::Sampler s;
    s.wrapS = wrap(t.wrap_u);
    s.wrapT = wrap(t.wrap_v);
    s.magFilter =
        t.filter == Texture::Filter::nearest ? TINYGLTF_TEXTURE_FILTER_NEAREST : TINYGLTF_TEXTURE_FILTER_LINEAR;
    s.minFilter = t.filter == Texture::Filter::nearest ? TINYGLTF_TEXTURE_FILTER_NEAREST
                                                       : TINYGLTF_TEXTURE_FILTER_LINEAR_MIPMAP_LINEAR;
    auto key = std::make_tuple(s.wrapS, s.wrapT, s.magFilter);
    auto it = samplers_.find(key);
    if (it != samplers_.end()) return it->second;
    model_.samplers.push_back(s);
    int index = int(model_.samplers.size()) - 1;
    samplers_[key] = index;
    return index;
  }

  // glTF texture of Scene texture ti (written once).
  int add_texture(int ti) {
    if (ti < 0 || ti >= int(scene_.textures.size())) return -1;
    auto it = textures_.find(ti);
    if (it != textures_.end()) return it->second;
    const Texture& t = scene_.textures[size_t(ti)];
    std::string ext;
    std::vector<uint8_t> bytes;
    try {
      bytes = texture_file(t, {"png", "jpg"}, &ext);
    } catch (const Error& e) {
      note(std::string("texture '") + t.name + "' cannot be read (" + e.what() +
           "); materials using it are untextured");
      textures_[ti] = -1;
      return -1;
    }
    if (!t.path.empty()) {
      const std::string src = lower_extension(t.path);
      if (src != ".png" && src != ".jpg" && src != ".jpeg") converted_.insert(t.name);
    }
    tinygltf::Image img;
    std::string base = texture_base_name(t);
    img.name = base;
    img.mimeType = ext == "jpg" ? "image/jpeg" : "image/png";
    if (options_.binary || options_.embed) {
      img.bufferView = add_view(bytes.data(), bytes.size(), 0);
      // tinygltf writes "target" only for the two buffer targets: none here.
    } else {
      std::string file = safe_file_name(stem_ + "_" + base) + "." + ext;
      for (int k = 2; used_files_.count(file); ++k)
        file = safe_file_name(stem_ + "_" + base + "_" + std::to_string(k)) + "." + ext;
      used_files_.insert(file);
      img.uri = file;
      out_.add(out_.beside(file), std::move(bytes));
    }
    model_.images.push_back(std::move(img));
    tinygltf::Texture gt;
    gt.name = t.name;
    gt.source = int(model_.images.size()) - 1;
    gt.sampler = add_sampler(t);
    Value::Object ex;
    if (t.lookup == Texture::Lookup::course) ex["lookup"] = Value(std::string("course"));
    if (!t.srgb) ex["srgb"] = Value(false);
    if (!ex.empty()) {
      gt.extras = rayform_extras(std::move(ex));
      raw_textures_.insert(t.name);
    }
    model_.textures.push_back(std::move(gt));
    int index = int(model_.textures.size()) - 1;
    textures_[ti] = index;
    return index;
  }

  // glTF material of Scene material mi; `textured` false: the copy for
  // primitives without uvs (glTF requires TEXCOORD_0 wherever a material has a
  // texture), which shows the diffuse colour as the renderer does without uvs.
  tinygltf::Material make_material(int mi, bool textured) {
    const Material& m = scene_.materials[size_t(mi)];
    tinygltf::Material gm;
    gm.name = textured ? m.name : m.name + " (no uvs)";
    const int tex = textured ? add_texture(m.diffuse_texture) : -1;
    // A course texture replaces the colour: base colour 1 x texel.
    const vec3 base = tex >= 0 && !m.texture_modulates ? vec3(1.f) : m.diffuse;
    PbrValues pbr = phong_to_pbr(base, m.specular, m.shininess);
    if (glm::any(glm::greaterThan(m.diffuse, vec3(1.f))) || glm::any(glm::lessThan(m.diffuse, vec3(0.f))))
      clamped_.insert(m.name);
    gm.pbrMetallicRoughness.baseColorFactor = nice_vector({pbr.base.r, pbr.base.g, pbr.base.b, pbr.base.a});
    gm.pbrMetallicRoughness.metallicFactor = nice(pbr.metallic);
    gm.pbrMetallicRoughness.roughnessFactor = nice(pbr.roughness);
    if (tex >= 0) {
      gm.pbrMetallicRoughness.baseColorTexture.index = tex;
      if (!m.uv_transform.is_identity()) {
        const GltfUvTransform t = scene_uv_transform_to_gltf(m.uv_transform);
        Value::Object tt;
        tt["offset"] = Value(Value::Array{num(t.offset.x), num(t.offset.y)});
        tt["rotation"] = num(t.rotation);
        tt["scale"] = Value(Value::Array{num(t.scale.x), num(t.scale.y)});
        gm.pbrMetallicRoughness.baseColorTexture.extensions["KHR_texture_transform"] = Value(std::move(tt));
        use_extension("KHR_texture_transform");
      }
    }
    if (m.emission != vec3(0.f)) {
      float peak = std::max({m.emission.r, m.emission.g, m.emission.b});
      vec3 e = m.emission;
      if (peak > 1.f) {
        e /= peak;
        gm.extensions["KHR_materials_emissive_strength"] = Value(Value::Object{{"emissiveStrength", num(peak)}});
        use_extension("KHR_materials_emissive_strength");
      }
      e = glm::clamp(e, vec3(0.f), vec3(1.f));
      gm.emissiveFactor = nice_vector({e.r, e.g, e.b});
    }
    if (m.alpha_cutoff >= 0.f) {
      gm.alphaMode = "MASK";
      gm.alphaCutoff = nice(std::min(m.alpha_cutoff, 1.f));
    }
    gm.doubleSided = m.double_sided;
    if (m.unlit) {
      gm.extensions["KHR_materials_unlit"] = Value(Value::Object{});
      use_extension("KHR_materials_unlit");
    }

    Value::Object ex;
    ex["phong"] = Value(Value::Object{
        {"diffuse", vec_value(m.diffuse)}, {"specular", vec_value(m.specular)}, {"shininess", num(m.shininess)}});
    ex["texture_modulates"] = Value(m.texture_modulates);
    ex["two_sided_lighting"] = Value(m.two_sided_lighting);
    if (m.refraction_index != 0.f) ex["refraction_index"] = num(m.refraction_index);
    if (m.emission != vec3(0.f)) ex["emission"] = vec_value(m.emission);
    if (m.alpha_cutoff >= 0.f) ex["alpha_cutoff"] = num(m.alpha_cutoff);
    if (m.bump_texture != invalid) {
      int bt = add_texture(m.bump_texture);
      if (bt >= 0) ex["bump_texture"] = Value(bt);
      if (textured) ++bump_maps_;
    }
    if (m.refraction_index != 0.f && textured) ++refractive_;
    // What was written, so that the reader can tell an edited material.
    ex["pbr"] = Value(Value::Object{{"base", Value(Value::Array{Value(gm.pbrMetallicRoughness.baseColorFactor[0]),
                                                                Value(gm.pbrMetallicRoughness.baseColorFactor[1]),
                                                                Value(gm.pbrMetallicRoughness.baseColorFactor[2]),
                                                                Value(gm.pbrMetallicRoughness.baseColorFactor[3])})},
                                    {"metallic", Value(gm.pbrMetallicRoughness.metallicFactor)},
                                    {"roughness", Value(gm.pbrMetallicRoughness.roughnessFactor)}});
    if (!textured) ex["variant_of"] = Value(mi);
    gm.extras = rayform_extras(std::move(ex));
    return gm;
  }

  void add_material(int mi) { model_.materials.push_back(make_material(mi, true)); }

  // The untextured copy of glTF material gi (made once).
  int untextured(int gi) {
    auto it = untextured_.find(gi);
    if (it != untextured_.end()) return it->second;
    model_.materials.push_back(make_material(gi, false));
    ++untextured_uses_;
    return untextured_[gi] = int(model_.materials.size()) - 1;
  }

  void use_extension(const std::string& e) {
    if (std::find(model_.extensionsUsed.begin(), model_.extensionsUsed.end(), e) == model_.extensionsUsed.end())
      model_.extensionsUsed.push_back(e);
  }

  // ---- cameras, lights, background ----------------------------------------------------

  std::string unique_name(const std::string& wanted, std::set<std::string>& used) {
    std::string n = wanted;
    for (int k = 2; used.count(n); ++k) n = wanted + "_" + std::to_string(k);
    used.insert(n);
    return n;
  }

  int add_camera(int ci) {
    const Camera& c = scene_.cameras[size_t(ci)];
    tinygltf::Camera gc;
    gc.name = unique_name(c.name.empty() ? "camera" : c.name, camera_names_);
    const float reach = 4.f * plane_quad_scale * extent_radius_ + glm::length(c.center - extent_center_);
    if (c.projection == Camera::Projection::perspective) {
      gc.type = "perspective";
      gc.perspective.yfov = double(radians(c.fov_deg));
      gc.perspective.znear = nice(1e-3f * extent_radius_);
      gc.perspective.zfar = nice(reach);
    } else {
      gc.type = "orthographic";
      gc.orthographic.xmag = nice(0.5f * c.ortho_height);
      gc.orthographic.ymag = nice(0.5f * c.ortho_height);
      gc.orthographic.znear = 0.0;
      gc.orthographic.zfar = nice(reach);
    }
    Value::Object ex;
    ex["name"] = Value(c.name);
    ex["aspect"] = Value(std::string(c.aspect == Camera::Aspect::stretch ? "stretch" : "fit"));
    ex["up_vector"] = Value(std::string(c.up_vector == Camera::UpVector::raw ? "raw" : "orthonormal"));
    ex["center"] = vec_value(c.center);
    ex["direction"] = vec_value(c.direction);
    ex["up"] = vec_value(c.up);
    ex["fov_deg"] = num(c.fov_deg);
    ex["ortho_height"] = num(c.ortho_height);
    gc.extras = rayform_extras(std::move(ex));
    if (c.aspect == Camera::Aspect::stretch) ++stretched_;
    if (c.up_vector == Camera::UpVector::raw) {
      vec3 w = glm::normalize(c.direction);
      vec3 v = glm::cross(glm::normalize(glm::cross(w, c.up)), w);
      if (glm::length(c.up - v) > 1e-6f) ++raw_up_;
    }
    model_.cameras.push_back(std::move(gc));
    tinygltf::Node n;
    n.name = model_.cameras.back().name;
    n.camera = int(model_.cameras.size()) - 1;
    n.translation = nice_vector({c.center.x, c.center.y, c.center.z});
    n.rotation = quaternion(look_basis(c.direction, c.up));
    return add_node(std::move(n));
  }

  int add_light(int li) {
    const Light& l = scene_.lights[size_t(li)];
    tinygltf::Light gl;
    gl.name = unique_name(l.name.empty() ? "light" : l.name, light_names_);
    float peak = std::max({l.color.r, l.color.g, l.color.b});
    vec3 color = peak > 0.f ? l.color / peak : vec3(1.f);
    float intensity = peak > 0.f ? peak : 0.f;
    if (peak > 0.f && peak <= 1.f) {  // keep colours in [0, 1] as they are
      color = l.color;
      intensity = 1.f;
    }
    color = glm::clamp(color, vec3(0.f), vec3(1.f));
    switch (l.kind) {
      case Light::Kind::directional: gl.type = "directional"; break;
      case Light::Kind::point: gl.type = "point"; break;
      case Light::Kind::spot: gl.type = "spot"; break;
    }
    if (l.kind != Light::Kind::directional) {
      if (l.falloff > 0.f) {
        // colour / (falloff d^2) = (intensity / d^2) x colour_gltf
        intensity /= l.falloff;
      } else {
        // No attenuation: match at the centre of the scene.
        float d = extent_.empty() ? 1.f : glm::length(extent_center_ - l.position);
        if (!(d > 0.f)) d = 1.f;
        intensity *= d * d;
        ++no_falloff_;
      }
      if (l.range > 0.f) gl.range = nice(l.range);
    }
    if (l.kind == Light::Kind::spot) {
      gl.spot.innerConeAngle = double(radians(l.spot_inner_deg));
      gl.spot.outerConeAngle = double(radians(l.spot_outer_deg));
    }
    gl.color = nice_vector({color.r, color.g, color.b});
    gl.intensity = nice(intensity);
    Value::Object ex;
    ex["name"] = Value(l.name);
    ex["color"] = vec_value(l.color);
    ex["falloff"] = num(l.falloff);
    ex["position"] = vec_value(l.position);
    ex["direction"] = vec_value(l.direction);
    gl.extras = rayform_extras(std::move(ex));
    model_.lights.push_back(std::move(gl));
    tinygltf::Node n;
    n.name = model_.lights.back().name;
    n.extensions["KHR_lights_punctual"] = Value(Value::Object{{"light", Value(int(model_.lights.size()) - 1)}});
    if (l.kind != Light::Kind::directional) n.translation = nice_vector({l.position.x, l.position.y, l.position.z});
    if (l.kind != Light::Kind::point && glm::length(l.direction) > 0.f)
      n.rotation = quaternion(look_basis(l.direction, vec3(0.f, 1.f, 0.f)));
    return add_node(std::move(n));
  }

  Value scene_extras() {
    const Background& b = scene_.background;
    Value::Object bg;
    bg["color"] = vec_value(b.color);
    bg["ambient"] = vec_value(b.ambient);
    if (b.cube_map[0] != invalid) {
      Value::Array faces;
      for (int f : b.cube_map) faces.push_back(Value(add_texture(f)));
      bg["cube_map"] = Value(std::move(faces));
      bg["cube_map_dir"] = Value(b.cube_map_dir);
    }
    return rayform_extras({{"version", Value(1)}, {"background", Value(std::move(bg))}});
  }

  // ---- messages ----------------------------------------------------------------------------

  void report() {
    if (spheres_)
      note(std::to_string(spheres_) + " sphere(s) tessellated (" + std::to_string(options_.sphere_segments) +
           " segments, " + std::to_string(tessellate_sphere(Sphere{}, options_.sphere_segments).triangle_count()) +
           " triangles each)" +
           (options_.shape_extras ? "; the exact sphere is kept in the primitive's extras"
                                  : "; no extras (--tessellate-only)"));
    if (planes_)
      note(std::to_string(planes_) + " plane(s) written as square quads of half-size " + format_float(plane_half_) +
           " around the scene" + (options_.shape_extras ? "; the exact plane is kept in the primitive's extras" : ""));
    if (untextured_uses_)
      note(std::to_string(untextured_uses_) +
           " textured material(s) also used by shapes without uvs: those use an "
           "untextured copy (glTF requires TEXCOORD_0 with a texture)");
    if (split_meshes_)
      note(std::to_string(split_meshes_) + " mesh(es) with several materials written as one primitive per material");
    if (sheared_)
      note(std::to_string(sheared_) +
           " transform(s) with a shear, which one glTF node cannot hold, written as two nodes (scale x rotation, "
           "rotation)");
    if (zero_normals_)
      note(std::to_string(zero_normals_) +
           " zero-length vertex normal(s) written as (0, 0, 1) (glTF requires unit normals)");
    if (!scene_.materials.empty())
      note(
          "Phong materials converted to metallic-roughness (docs/convert.md); the exact Phong values are kept in the "
          "material extras");
    if (!clamped_.empty())
      note("materials " + quoted_list(clamped_) + ": diffuse colour outside [0, 1] clamped in baseColorFactor");
    if (!raw_textures_.empty())
      note("textures " + quoted_list(raw_textures_) +
           ": course textures (raw texels, texel centres on whole numbers) are kept as they are, the course's reading "
           "in "
           "the texture extras; other viewers read them as sRGB with the usual texel centres");
    if (!converted_.empty())
      note("textures " + quoted_list(converted_) + " converted to PNG (glTF holds PNG and JPEG)");
    if (bump_maps_)
      note(
          std::to_string(bump_maps_) +
          " bump map(s) kept as textures named in the material extras only (glTF has height maps only as normal maps)");
    if (refractive_) note(std::to_string(refractive_) + " refraction index(es) kept in the material extras only");
    if (stretched_)
      note(
          "camera: the course stretches its view to the image (no aspect correction); glTF cameras keep the aspect, "
          "which is the same picture for square images; the course camera is kept in the camera extras");
    if (raw_up_) note("camera: the 2019 dialect's raw (not orthogonal) up vector is kept in the camera extras only");
    if (no_falloff_)
      note(std::to_string(no_falloff_) +
           " point light(s) without falloff (course): glTF lights fall off with the distance squared; the intensity is "
           "set to match at the centre of the scene, the exact light in the light extras");
    const Background& b = scene_.background;
    if (b.color != Background{}.color || b.ambient != vec3(0.f) || b.cube_map[0] != invalid)
      note("background colour, ambient light and cube map have no glTF equivalent: kept in the scene's extras");
  }

  // ---- output ---------------------------------------------------------------------------

  // The length a .glb's header declares (0 when the header is missing).
  static uint64_t glb_length(const std::string& file) {
    std::ifstream in(file, std::ios::binary);
    unsigned char head[12] = {};
    if (!in.read(reinterpret_cast<char*>(head), sizeof head)) return 0;
    return uint64_t(head[8]) | uint64_t(head[9]) << 8 | uint64_t(head[10]) << 16 | uint64_t(head[11]) << 24;
  }

  // A file tinygltf wrote: `bytes` long (when not 0), complete JSON (when
  // `json`), then synced; else the write failed (a full disk, most likely).
  void check_written(const std::string& file, uint64_t bytes, bool json) const {
    std::error_code ec;
    const uint64_t size = fs::file_size(file, ec);
    bool complete = !ec && size > 0 && (bytes == 0 || size == bytes);
    if (complete && json) {
      std::ifstream in(file, std::ios::binary);
      complete = nlohmann::json::accept(in);
    }
    std::string error = complete ? "" : "the file was cut short (disk full?)";
    if (complete && !sync_file(file, &error)) complete = false;
    if (!complete) throw Error(path_ + ": cannot write (" + error + ")");
  }

  SaveResult save() {
    if (!buffer_.empty()) {
      tinygltf::Buffer b;
      b.data = std::move(buffer_);
      if (!options_.binary && !options_.embed) b.uri = stem_ + ".bin";
      model_.buffers.push_back(std::move(b));
    }
    const std::string dir = out_.temp_dir();
    const std::string ext = options_.binary ? ".glb" : ".gltf";
    const std::string temp_main = (fs::path(dir) / (stem_ + ext)).string();
    tinygltf::TinyGLTF writer;
    writer.SetImageWriter(&keep_image_uri, nullptr);
    if (!writer.WriteGltfSceneToFile(&model_, temp_main, /*embedImages*/ false, /*embedBuffers*/ options_.embed,
                                     /*prettyPrint*/ true, /*writeBinary*/ options_.binary))
      throw Error(path_ + ": cannot write (tinygltf failed to write '" + temp_main + "')");
    std::error_code ec;
    if (!fs::is_regular_file(temp_main, ec)) throw Error(path_ + ": cannot write (tinygltf wrote nothing)");
    // tinygltf does not check its writes: a full disk leaves short files. Each
    // is checked for its whole length, then synced (image/checked_write.h).
    check_written(temp_main, options_.binary ? glb_length(temp_main) : 0, !options_.binary);
    if (!model_.buffers.empty() && !model_.buffers[0].uri.empty()) {
      std::string bin = (fs::path(dir) / model_.buffers[0].uri).string();
      if (!fs::is_regular_file(bin, ec)) throw Error(path_ + ": cannot write the buffer file " + model_.buffers[0].uri);
      check_written(bin, model_.buffers[0].data.size(), false);
      out_.add_written(out_.beside(model_.buffers[0].uri), bin);
    }
    out_.add_written(path_, temp_main);
    SaveResult r;
    r.files = out_.commit();
    for (const tinygltf::Mesh& m : model_.meshes)  // as readers count: each mesh once, every primitive
      for (const tinygltf::Primitive& p : m.primitives)
        r.stored_triangles += model_.accessors[size_t(p.indices)].count / 3;
    return r;
  }

  const Scene& scene_;
  std::string path_, name_, stem_;
  GltfWriteOptions options_;
  std::vector<std::string>* messages_;
  OutputFiles out_;
  tinygltf::Model model_;
  std::vector<uint8_t> buffer_;
  Bounds3 extent_;
  vec3 extent_center_{0.f};
  float extent_radius_ = 1.f;
  std::vector<uint8_t> on_path_;
  std::map<std::vector<PrimitiveRef>, int> meshes_;
  std::map<int, Geometry> sphere_geometry_;
  std::map<std::pair<int, int>, Geometry> mesh_geometry_;
  std::map<std::string, Geometry> stored_;  // by content
  std::map<int, int> untextured_;           // glTF material -> its copy without texture
  int untextured_uses_ = 0;
  std::map<int, int> textures_;
  std::map<std::tuple<int, int, int>, int> samplers_;
  std::set<std::string> used_files_, camera_names_, light_names_;
  std::set<std::string> clamped_, raw_textures_, converted_;
  size_t zero_normals_ = 0;
  int spheres_ = 0, planes_ = 0, split_meshes_ = 0, sheared_ = 0, bump_maps_ = 0, refractive_ = 0;
  int stretched_ = 0, raw_up_ = 0, no_falloff_ = 0;
  float plane_half_ = 0.f;
};

}  // namespace

SaveResult write_gltf_scene(const Scene& scene, const std::string& path, const GltfWriteOptions& options,
                            std::vector<std::string>* messages) {
  require_scene_root(scene, path);
  return GltfBuilder(scene, path, options, messages).write();
}

}  // namespace rayform
