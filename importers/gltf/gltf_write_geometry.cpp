// The glTF writer's geometry (GltfWriter, gltf_writer_internal.h): the binary
// buffer's views and accessors, meshes' vertices and faces (per material)
// stored once by content, spheres, planes and triangles tessellated with
// their exact form in extras, and glTF meshes shared where the same shapes
// recur.
#include "rayform/importers/gltf/gltf_writer_internal.h"
#include "rayform/base/error.h"
#include "rayform/importers/shape_tessellation.h"

#include <algorithm>
#include <cmath>

namespace rayform::gltf_detail {

namespace {

constexpr int array_buffer = TINYGLTF_TARGET_ARRAY_BUFFER;
constexpr int element_buffer = TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER;

}  // namespace

int GltfWriter::add_view(const void* data, size_t bytes, int target) {
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

int GltfWriter::add_accessor(int view, int component, size_t count, int type, std::vector<double> min,
                             std::vector<double> max) {
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

int GltfWriter::add_vec3s(const std::vector<vec3>& v, bool bounds) {
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

// The accessors of a mesh (restricted to the faces of one material when
// `only_material` is not invalid and the mesh has face materials).
GltfWriter::Geometry GltfWriter::mesh_geometry(const Mesh& m, int only_material) {
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
    if (c >= m.positions.size()) throw Error(context_.path + ": mesh '" + m.name + "' has an index out of range");
    if (remap[c] < 0) {
      remap[c] = int64_t(used.size());
      used.push_back(c);
    }
    c = uint32_t(remap[c]);
  }
  std::vector<vec3> pos, nor, col;
  std::vector<vec2> uv, uv1;
  std::vector<vec4> tan;
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
    // glTF's v runs down the image, the Scene's up.
    if (m.uvs.size() == m.positions.size()) uv.push_back(vec2(m.uvs[i].x, 1.f - m.uvs[i].y));
    if (m.uvs1.size() == m.positions.size()) uv1.push_back(vec2(m.uvs1[i].x, 1.f - m.uvs1[i].y));
    // Tangents as the Scene holds them: glTF's TANGENT (bitangent = w cross(normal, tangent)).
    if (m.tangents.size() == m.positions.size() && m.normals.size() == m.positions.size()) tan.push_back(m.tangents[i]);
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
  append(uv1.data(), uv1.size() * sizeof(vec2));
  append(tan.data(), tan.size() * sizeof(vec4));
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
  if (!uv1.empty()) {
    int view = add_view(uv1.data(), uv1.size() * sizeof(vec2), array_buffer);
    g.uv1 = add_accessor(view, TINYGLTF_COMPONENT_TYPE_FLOAT, uv1.size(), TINYGLTF_TYPE_VEC2);
  }
  if (!tan.empty()) {
    int view = add_view(tan.data(), tan.size() * sizeof(vec4), array_buffer);
    g.tangent = add_accessor(view, TINYGLTF_COMPONENT_TYPE_FLOAT, tan.size(), TINYGLTF_TYPE_VEC4);
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

tinygltf::Primitive GltfWriter::primitive(const Geometry& g, int material) {
  tinygltf::Primitive p;
  p.mode = TINYGLTF_MODE_TRIANGLES;
  p.indices = g.indices;
  p.attributes["POSITION"] = g.position;
  if (g.normal >= 0) p.attributes["NORMAL"] = g.normal;
  if (g.uv >= 0) p.attributes["TEXCOORD_0"] = g.uv;
  if (g.uv1 >= 0) p.attributes["TEXCOORD_1"] = g.uv1;
  if (g.tangent >= 0) p.attributes["TANGENT"] = g.tangent;
  if (g.color >= 0) p.attributes["COLOR_0"] = g.color;
  // A texture needs its uv set on every primitive that uses the material.
  if (material >= 0) {
    const int needed = uv_sets_needed_[size_t(material)];
    const int present = (g.uv >= 0 ? uv_set_0 : 0) | (g.uv1 >= 0 ? uv_set_1 : 0);
    if (needed & ~present) material = untextured(material);
  }
  p.material = material;
  return p;
}

int GltfWriter::gltf_material(int m) const {
  return m >= 0 && m < int(scene_.materials.size()) ? m : -1;  // -1: glTF's default material
}

// The primitives of one shape (several for a mesh with face materials).
std::vector<tinygltf::Primitive> GltfWriter::shape_primitives(const PrimitiveRef& r) {
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
int GltfWriter::add_mesh(const std::vector<PrimitiveRef>& refs, const std::string& name) {
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

}  // namespace rayform::gltf_detail
