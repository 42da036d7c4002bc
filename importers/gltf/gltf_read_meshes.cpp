// The glTF reader's meshes (GltfReader, gltf_reader_internal.h): each
// glTF mesh's primitives as Scene meshes and shape nodes, once per morph
// weights and skin; attributes from accessors or a KHR_draco_mesh_compression
// stream (TEXCOORD_0 and TEXCOORD_1, TANGENT, COLOR_0 besides positions
// and normals), morph targets, linear blend skinning, and strips and fans as
// triangle lists.
#include "rayform/importers/gltf/gltf_compression.h"
#include "rayform/importers/gltf/gltf_file_access.h"
#include "rayform/importers/gltf/gltf_material.h"
#include "rayform/importers/gltf/gltf_reader_internal.h"

#include <algorithm>
#include <cmath>

namespace rayform::gltf_detail {

// A Draco-compressed primitive, decoded: attribute name -> index into mesh.attributes.
struct GltfReader::DracoPrimitive {
  DracoMesh mesh;
  std::map<std::string, int> slots;
  int indices = -1;  // the primitive's index accessor (adapt_json_for_tinygltf moved it)
};

// KHR_draco_mesh_compression of `prim`, decoded; nullptr when it has none.
std::unique_ptr<GltfReader::DracoPrimitive> GltfReader::decode_draco_primitive(const tinygltf::Primitive& prim,
                                                                               const std::string& where) {
  auto it = prim.extensions.find("KHR_draco_mesh_compression");
  if (it == prim.extensions.end()) return nullptr;
  const std::string dw = where + ".extensions.KHR_draco_mesh_compression";
  const tinygltf::Value& e = it->second;
  if (!e.IsObject() || !e.Has("bufferView") || !e.Get("bufferView").IsNumber() || !e.Has("attributes") ||
      !e.Get("attributes").IsObject())
    fail(dw + ": expected an object with a \"bufferView\" and \"attributes\"");
  const GltfAccessors::View bytes = accessors_.view(e.Get("bufferView").GetNumberAsInt(), dw + ".bufferView");
  auto out = std::make_unique<DracoPrimitive>();
  std::vector<int> ids;
  const tinygltf::Value& attributes = e.Get("attributes");
  for (const std::string& name : attributes.Keys()) {
    const tinygltf::Value& id = attributes.Get(name);
    if (!id.IsNumber() || id.GetNumberAsInt() < 0)
      fail(dw + ".attributes." + name + ": expected a Draco attribute id (an integer from 0 to 2147483647)" +
           (id.IsString() ? ", got " + id.Get<std::string>() : std::string()));
    if (!prim.attributes.count(name))
      fail(dw + ".attributes." + name + ": the primitive has no accessor for this attribute");
    out->slots[name] = int(ids.size());
    ids.push_back(id.GetNumberAsInt());
  }
  if (e.Has(draco_indices_key) && e.Get(draco_indices_key).IsNumber())
    out->indices = e.Get(draco_indices_key).GetNumberAsInt();
  out->mesh = decode_draco(bytes.data, bytes.length, ids, path_ + ": " + dw);
  use_extension("KHR_draco_mesh_compression");
  return out;
}

// Attribute `name` of `prim` as floats: from the Draco mesh when it holds
// the attribute, else from its accessor. Types and formats checked on the
// accessor either way.
GltfAccessors::Floats GltfReader::attribute(const tinygltf::Primitive& prim, const DracoPrimitive* draco,
                                            const std::string& name, const std::string& where,
                                            std::initializer_list<int> types, uint32_t formats) {
  const int a = prim.attributes.at(name);
  const std::string aw = where + ".attributes." + name;
  if (!draco || !draco->slots.count(name)) return accessors_.read_floats(a, aw, types, formats);
  const tinygltf::Accessor& acc = accessors_.check_format(a, aw, types, formats);
  const DracoAttribute& d = draco->mesh.attributes[size_t(draco->slots.at(name))];
  GltfAccessors::Floats f;
  f.components = gltf_type_components(acc.type);
  f.count = draco->mesh.vertex_count;
  if (d.components != f.components)
    fail(aw + ": the Draco attribute has " + std::to_string(d.components) + " components, the accessor " +
         std::to_string(f.components));
  if (acc.count != f.count)
    fail(aw + " (" + idx("accessors", a) + "): the Draco stream decodes to " + std::to_string(f.count) +
         " vertices but the accessor's count is " + std::to_string(acc.count));
  f.values = d.values;
  if (acc.normalized)
    for (float& v : f.values) v = gltf_normalize_integer(v, acc.componentType);
  return f;
}

// How node `skinned_node` poses its skin: per joint, world(joint) x inverseBindMatrix.
std::vector<mat4> GltfReader::skin_joint_matrices(int skinned_node) {
  const tinygltf::Node& n = model_.nodes[size_t(skinned_node)];
  const std::string sw = idx("skins", n.skin);
  if (n.skin < 0 || size_t(n.skin) >= model_.skins.size())
    fail(idx("nodes", skinned_node) + ".skin: skin " + std::to_string(n.skin) + " does not exist (the file has " +
         std::to_string(model_.skins.size()) + " skins)");
  const tinygltf::Skin& skin = model_.skins[size_t(n.skin)];
  std::vector<mat4> inverse_bind(skin.joints.size(), mat4(1.f));
  if (skin.inverseBindMatrices >= 0) {
    GltfAccessors::Floats ibm = accessors_.read_floats(skin.inverseBindMatrices, sw + ".inverseBindMatrices",
                                                       {TINYGLTF_TYPE_MAT4}, format_float);
    if (ibm.count < skin.joints.size())
      fail(sw + ".inverseBindMatrices: " + std::to_string(ibm.count) + " matrices for " +
           std::to_string(skin.joints.size()) + " joints");
    for (size_t j = 0; j < skin.joints.size(); ++j)
      for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r) inverse_bind[j][c][r] = ibm.values[16 * j + size_t(4 * c + r)];
  }
  std::vector<mat4> out(skin.joints.size());
  for (size_t j = 0; j < skin.joints.size(); ++j) {
    const int joint = skin.joints[j];
    if (joint < 0 || size_t(joint) >= model_.nodes.size())
      fail(sw + ".joints[" + std::to_string(j) + "]: node " + std::to_string(joint) + " does not exist");
    out[j] = node_world(joint) * inverse_bind[j];
    if (!is_finite(vec3(out[j][0])) || !is_finite(vec3(out[j][1])) || !is_finite(vec3(out[j][2])) ||
        !is_finite(vec3(out[j][3])))
      fail(sw + ".joints[" + std::to_string(j) + "]: the joint's matrix is not finite");
  }
  return out;
}

// The Scene meshes of glTF mesh `mi` at morph `weights`, posed by the skin
// of node `skinned_node` (invalid: not skinned), as shape nodes; converted
// once per combination.
const std::vector<int>& GltfReader::mesh_shapes(int mi, const std::vector<float>& weights, int skinned_node) {
  MeshKey key{mi, skinned_node, weights};
  auto it = mesh_shapes_.find(key);
  if (it != mesh_shapes_.end()) return it->second;
  const tinygltf::Mesh& gm = model_.meshes[size_t(mi)];
  count_mesh_copy(mi);
  std::vector<mat4> joints;
  if (skinned_node != invalid) joints = skin_joint_matrices(skinned_node);
  std::vector<int> shapes, meshes;
  for (size_t j = 0; j < gm.primitives.size(); ++j) {
    const std::string where = idx("meshes", mi) + "." + idx("primitives", long(j));
    std::string name = gm.name.empty() ? idx("meshes", mi) : gm.name;
    // append, not name += "#" + ...: GCC 12 warns (-Wrestrict, a false positive) on that here
    if (gm.primitives.size() > 1) name.append("#").append(std::to_string(j));
    Primitive p =
        convert_primitive(gm.primitives[j], where, name, weights, skinned_node != invalid ? &joints : nullptr);
    if (p.mesh == invalid) continue;
    meshes.push_back(p.mesh);
    Node shape;
    shape.kind = Node::Kind::shape;
    shape.name = scene_.meshes[size_t(p.mesh)].name;
    shape.shape_kind = ShapeKind::mesh;
    shape.shape = p.mesh;
    shape.material = p.material;
    shapes.push_back(add_node(std::move(shape)));
  }
  // The extras of a primitive describe its first, unposed conversion.
  if (extras_primitives_[size_t(mi)].empty() && meshes.size() == gm.primitives.size() && skinned_node == invalid)
    extras_primitives_[size_t(mi)] = meshes;
  return mesh_shapes_.emplace(std::move(key), std::move(shapes)).first->second;
}

// Gltf mesh `mi`'s vertices and triangles, as its accessors declare them,
// added to those built so far and checked against the limits before the
// mesh is converted (again: once per morph weights and skin).
void GltfReader::count_mesh_copy(int mi) {
  const tinygltf::Mesh& gm = model_.meshes[size_t(mi)];
  uint64_t vertices = 0, triangles = 0;
  for (size_t j = 0; j < gm.primitives.size(); ++j) {
    const tinygltf::Primitive& prim = gm.primitives[j];
    auto position = prim.attributes.find("POSITION");
    const int mode = prim.mode == -1 ? TINYGLTF_MODE_TRIANGLES : prim.mode;
    const bool triangles_mode =
        mode == TINYGLTF_MODE_TRIANGLES || mode == TINYGLTF_MODE_TRIANGLE_STRIP || mode == TINYGLTF_MODE_TRIANGLE_FAN;
    if (position == prim.attributes.end() || !triangles_mode) continue;  // skipped by convert_primitive
    const std::string where = idx("meshes", mi) + "." + idx("primitives", long(j));
    const uint64_t nv = accessors_.accessor(position->second, where + ".attributes.POSITION").count;
    const uint64_t corners = prim.indices >= 0 ? accessors_.accessor(prim.indices, where + ".indices").count : nv;
    const uint64_t t = mode == TINYGLTF_MODE_TRIANGLES ? corners / 3 : corners < 2 ? 0 : corners - 2;  // at most
    // Saturating: a count past any limit stays past it.
    vertices = nv > UINT64_MAX - vertices ? UINT64_MAX : vertices + nv;
    triangles = t > UINT64_MAX - triangles ? UINT64_MAX : triangles + t;
  }
  // Each node's morph weights and each skin build the mesh again.
  const std::string mw = idx("meshes", mi) + (vertices_ ? ", with the meshes built before it" : "");
  if (!fits_in(vertices_, vertices, options_.limits.vertices))
    fail(mw + ": " +
         limit_exceeded("vertices", vertices > UINT64_MAX - vertices_ ? UINT64_MAX : vertices_ + vertices,
                        options_.limits.vertices));
  if (!fits_in(triangles_, triangles, options_.limits.triangles))
    fail(mw + ": " +
         limit_exceeded("triangles", triangles > UINT64_MAX - triangles_ ? UINT64_MAX : triangles_ + triangles,
                        options_.limits.triangles));
  vertices_ += vertices;
  triangles_ += triangles;
}

Primitive GltfReader::convert_primitive(const tinygltf::Primitive& prim, const std::string& where,
                                        const std::string& name, const std::vector<float>& weights,
                                        const std::vector<mat4>* joints) {
  int mode = prim.mode == -1 ? TINYGLTF_MODE_TRIANGLES : prim.mode;
  switch (mode) {
    case TINYGLTF_MODE_TRIANGLES:
    case TINYGLTF_MODE_TRIANGLE_STRIP:
    case TINYGLTF_MODE_TRIANGLE_FAN: break;
    case TINYGLTF_MODE_POINTS:
    case TINYGLTF_MODE_LINE:
    case TINYGLTF_MODE_LINE_LOOP:
    case TINYGLTF_MODE_LINE_STRIP:
      warn(where + ": " + (mode == TINYGLTF_MODE_POINTS ? "points are" : "lines are") +
           " not rendered; primitive skipped");
      return {};
    default: fail(where + ".mode: " + std::to_string(mode) + " is not a primitive mode (0 to 6)");
  }
  const int mat = material(prim.material, where + ".material");
  if (!prim.attributes.count("POSITION")) {
    warn(where + ": no POSITION attribute; primitive skipped");
    return {};
  }
  const std::unique_ptr<DracoPrimitive> draco = decode_draco_primitive(prim, where);
  Mesh mesh;
  mesh.name = name;
  mesh.source_path = path_;
  const GltfAccessors::Floats positions =
      attribute(prim, draco.get(), "POSITION", where, {TINYGLTF_TYPE_VEC3}, formats_position);
  const size_t nv = positions.count;
  mesh.positions.resize(nv);
  for (size_t i = 0; i < nv; ++i)
    mesh.positions[i] = vec3(positions.values[3 * i], positions.values[3 * i + 1], positions.values[3 * i + 2]);
  auto same_count = [&](size_t n, const std::string& aw) {
    if (n != nv) fail(aw + ": " + std::to_string(n) + " elements, but POSITION has " + std::to_string(nv));
  };
  auto read_vec3s = [&](const GltfAccessors::Floats& f, std::vector<vec3>& out) {
    out.resize(nv);
    const size_t nc = size_t(f.components);
    for (size_t i = 0; i < nv; ++i) out[i] = vec3(f.values[nc * i], f.values[nc * i + 1], f.values[nc * i + 2]);
  };
  if (prim.attributes.count("NORMAL")) {
    GltfAccessors::Floats f = attribute(prim, draco.get(), "NORMAL", where, {TINYGLTF_TYPE_VEC3}, formats_normal);
    same_count(f.count, where + ".attributes.NORMAL");
    read_vec3s(f, mesh.normals);
  }
  if (prim.attributes.count("TANGENT")) read_tangents(prim, draco.get(), where, mesh);
  apply_morph_targets(prim, where, weights, mesh);
  if (joints) apply_skin(prim, draco.get(), where, *joints, mesh);
  for (size_t i = 0; i < nv; ++i)
    if (!is_finite(mesh.positions[i])) {
      const vec3& p = mesh.positions[i];
      fail(where + ".attributes.POSITION: vertex " + std::to_string(i) + " is not finite (" + std::to_string(p.x) +
           ", " + std::to_string(p.y) + ", " + std::to_string(p.z) + ")");
    }
  for (vec3& n : mesh.normals) {
    const float len = glm::length(n);
    n = len > 0.f && std::isfinite(len) ? n / len : vec3(0.f);
  }
  // Without NORMAL, normals stay empty: the renderer's face normals are the
  // flat normals the specification asks for.
  auto read_uvs = [&](const std::string& uv_name, std::vector<vec2>& out) {
    if (!prim.attributes.count(uv_name)) return;
    GltfAccessors::Floats f = attribute(prim, draco.get(), uv_name, where, {TINYGLTF_TYPE_VEC2}, formats_texcoord);
    same_count(f.count, where + ".attributes." + uv_name);
    out.resize(nv);
    for (size_t i = 0; i < nv; ++i) out[i] = vec2(f.values[2 * i], 1.f - f.values[2 * i + 1]);  // v = 1 at the top
  };
  read_uvs("TEXCOORD_0", mesh.uvs);
  read_uvs("TEXCOORD_1", mesh.uvs1);
  for (const auto& [name, slot] : gltf_named_texture_slots(scene_.materials[size_t(mat)].pbr))
    if (slot->used() && (slot->texcoord == 0 ? mesh.uvs : mesh.uvs1).empty())
      warn(where + ": the material's " + name + " uses TEXCOORD_" + std::to_string(slot->texcoord) +
           " but the primitive has none; drawn without it");
  if (prim.attributes.count("COLOR_0")) {
    GltfAccessors::Floats f =
        attribute(prim, draco.get(), "COLOR_0", where, {TINYGLTF_TYPE_VEC3, TINYGLTF_TYPE_VEC4}, formats_color);
    same_count(f.count, where + ".attributes.COLOR_0");
    read_vec3s(f, mesh.colors);  // linear already; alpha is not used
  }

  std::vector<uint32_t> order;
  const std::string iw = where + ".indices";
  if (draco) {
    order = draco->mesh.indices;
    const int indices = prim.indices != -1 ? prim.indices : draco->indices;
    if (indices != -1 && accessors_.accessor(indices, iw).count != order.size())
      fail(iw + " (" + idx("accessors", indices) + "): the Draco stream decodes to " + std::to_string(order.size()) +
           " indices but the accessor's count is " + std::to_string(accessors_.accessor(indices, iw).count));
  } else if (prim.indices != -1) {
    order = accessors_.read_indices(prim.indices, iw);
  } else {
    order.resize(nv);
    for (size_t i = 0; i < nv; ++i) order[i] = uint32_t(i);
  }
  for (size_t k = 0; k < order.size(); ++k)
    if (order[k] >= nv)
      fail(iw + ": index " + std::to_string(order[k]) + " (element " + std::to_string(k) +
           ") is out of range (the primitive has " + std::to_string(nv) + " vertices)");
  mesh.indices = triangulate(order, mode, where);
  if (mesh.indices.empty()) {
    warn(where + ": no triangles; primitive skipped");
    return {};
  }
  scene_.meshes.push_back(std::move(mesh));
  return Primitive{int(scene_.meshes.size()) - 1, mat};
}

// TANGENT (VEC4; the same formats as NORMAL: float, or KHR_mesh_quantization's
// normalised bytes and shorts) as Mesh::tangents: xyz normalised (a zero
// vector stays zero), w the bitangent's sign. The specification's w is +1 or
// -1; the sign of any other nonzero w is kept (a value rounded on its way
// through some tool), while a w of 0 or a non-finite value is an error naming
// the vertex.
void GltfReader::read_tangents(const tinygltf::Primitive& prim, const DracoPrimitive* draco, const std::string& where,
                               Mesh& mesh) {
  const std::string aw = where + ".attributes.TANGENT";
  const GltfAccessors::Floats f = attribute(prim, draco, "TANGENT", where, {TINYGLTF_TYPE_VEC4}, formats_normal);
  const size_t nv = mesh.positions.size();
  if (f.count != nv) fail(aw + ": " + std::to_string(f.count) + " elements, but POSITION has " + std::to_string(nv));
  mesh.tangents.resize(nv);
  for (size_t i = 0; i < nv; ++i) {
    const vec4 t(f.values[4 * i], f.values[4 * i + 1], f.values[4 * i + 2], f.values[4 * i + 3]);
    if (!is_finite(vec3(t)) || !std::isfinite(t.w) || t.w == 0.f)
      fail(aw + ": vertex " + std::to_string(i) + " is (" + std::to_string(t.x) + ", " + std::to_string(t.y) + ", " +
           std::to_string(t.z) + ", " + std::to_string(t.w) + "): expected finite xyz and w = 1 or -1");
    const float len = glm::length(vec3(t));
    mesh.tangents[i] = vec4(len > 0.f && std::isfinite(len) ? vec3(t) / len : vec3(0.f), t.w > 0.f ? 1.f : -1.f);
  }
}

// Morph targets at `weights`: POSITION and NORMAL displaced by the
// weighted sum of the targets' deltas (other target attributes are not used).
void GltfReader::apply_morph_targets(const tinygltf::Primitive& prim, const std::string& where,
                                     const std::vector<float>& weights, Mesh& mesh) {
  const size_t nv = mesh.positions.size();
  for (size_t t = 0; t < prim.targets.size(); ++t) {
    const float w = t < weights.size() ? weights[t] : 0.f;
    if (w == 0.f) continue;
    const std::string tw = where + "." + idx("targets", long(t));
    for (const char* name : {"POSITION", "NORMAL"}) {
      auto it = prim.targets[t].find(name);
      if (it == prim.targets[t].end()) continue;
      std::vector<vec3>& values = std::string(name) == "POSITION" ? mesh.positions : mesh.normals;
      if (values.empty()) continue;  // a NORMAL delta without normals
      const std::string aw = tw + "." + name;
      GltfAccessors::Floats d = accessors_.read_floats(it->second, aw, {TINYGLTF_TYPE_VEC3}, formats_morph_delta);
      if (d.count != nv)
        fail(aw + ": " + std::to_string(d.count) + " elements, but POSITION has " + std::to_string(nv));
      for (size_t i = 0; i < nv; ++i) values[i] += w * vec3(d.values[3 * i], d.values[3 * i + 1], d.values[3 * i + 2]);
    }
  }
}

// Linear blend skinning into world space: p' = sum_k w_k J_{j_k} p over
// the sets JOINTS_n / WEIGHTS_n (weights renormalised to sum 1); normals by
// the blended matrix's inverse transpose (renormalised later), tangents by its
// linear part (renormalised here; their sign kept).
void GltfReader::apply_skin(const tinygltf::Primitive& prim, const DracoPrimitive* draco, const std::string& where,
                            const std::vector<mat4>& joints, Mesh& mesh) {
  const size_t nv = mesh.positions.size();
  std::vector<mat4> blend(nv, mat4(0.f));
  std::vector<float> total(nv, 0.f);
  for (int set = 0;; ++set) {
    const std::string jn = "JOINTS_" + std::to_string(set), wn = "WEIGHTS_" + std::to_string(set);
    if (!prim.attributes.count(jn) || !prim.attributes.count(wn)) break;
    GltfAccessors::Floats j = attribute(prim, draco, jn, where, {TINYGLTF_TYPE_VEC4}, formats_joints);
    GltfAccessors::Floats w = attribute(prim, draco, wn, where, {TINYGLTF_TYPE_VEC4}, formats_weights);
    if (j.count != nv || w.count != nv)
      fail(where + ".attributes." + jn + ": " + std::to_string(std::min(j.count, w.count)) +
           " elements, but POSITION has " + std::to_string(nv));
    for (size_t i = 0; i < nv; ++i)
      for (size_t k = 0; k < 4; ++k) {
        const float weight = w.values[4 * i + k];
        if (weight == 0.f) continue;
        const size_t joint = size_t(j.values[4 * i + k]);
        if (joint >= joints.size())
          fail(where + ".attributes." + jn + ": vertex " + std::to_string(i) + " names joint " + std::to_string(joint) +
               " but the skin has " + std::to_string(joints.size()));
        blend[i] += weight * joints[joint];
        total[i] += weight;
      }
  }
  for (size_t i = 0; i < nv; ++i) {
    if (!(total[i] > 0.f)) continue;  // no influence: left in place
    const mat4 m = blend[i] / total[i];
    mesh.positions[i] = transform_point(m, mesh.positions[i]);
    if (!mesh.normals.empty()) mesh.normals[i] = glm::transpose(glm::inverse(mat3(m))) * mesh.normals[i];
    if (!mesh.tangents.empty()) {
      const vec3 t = mat3(m) * vec3(mesh.tangents[i]);
      const float len = glm::length(t);
      mesh.tangents[i] = vec4(len > 0.f && std::isfinite(len) ? t / len : vec3(0.f), mesh.tangents[i].w);
    }
  }
}

// Triangle lists per the specification's vertex order:
//   strips: p_i = {v_i, v_{i+(1+i%2)}, v_{i+(2-i%2)}}; fans: p_i = {v_{i+1}, v_{i+2}, v_0}.
// Strip and fan triangles that repeat a vertex (joins) are dropped.
std::vector<uint32_t> GltfReader::triangulate(const std::vector<uint32_t>& v, int mode, const std::string& where) {
  std::vector<uint32_t> out;
  const size_t n = v.size();
  auto push = [&](uint32_t a, uint32_t b, uint32_t c, bool drop_degenerate) {
    if (drop_degenerate && (a == b || b == c || a == c)) return;
    out.insert(out.end(), {a, b, c});
  };
  if (mode == TINYGLTF_MODE_TRIANGLES) {
    if (n % 3 != 0)
      warn(where + ": " + std::to_string(n) + " vertices is not a multiple of 3; the last " + std::to_string(n % 3) +
           " are ignored");
    out.reserve(n - n % 3);
    for (size_t i = 0; i + 2 < n; i += 3) push(v[i], v[i + 1], v[i + 2], false);
  } else if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
    for (size_t i = 0; i + 2 < n; ++i) push(v[i], v[i + 1 + i % 2], v[i + 2 - i % 2], true);
  } else {
    for (size_t i = 0; i + 2 < n; ++i) push(v[i + 1], v[i + 2], v[0], true);
  }
  return out;
}

}  // namespace rayform::gltf_detail
