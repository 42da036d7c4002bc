// The course writer's meshes (CourseWriter, course_writer_internal.h): each
// part of a triangle mesh as an OBJ file in the course's own subset, its
// vertices shared where the course's normals will match the source's, and the
// vertex normals the course computes (course_normals).
#include "rayform/importers/course_txt/course_writer_internal.h"

#include "rayform/importers/course_txt/course_mesh.h"
#include "rayform/base/error.h"
#include "rayform/importers/text_format.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <map>
#include <numbers>
#include <sstream>
#include <tuple>

namespace rayform {

std::vector<vec3> course_normals(const Mesh& mesh, const std::vector<uint32_t>& share, CourseDialect dialect) {
  std::vector<uint32_t> corners(mesh.indices.size());
  for (size_t c = 0; c < corners.size(); ++c) corners[c] = share[mesh.indices[c]];
  const std::vector<vec3> by_position = course_position_normals(mesh.positions, corners, dialect);
  std::vector<vec3> out(mesh.positions.size());
  for (size_t i = 0; i < out.size(); ++i) out[i] = by_position[share[i]];
  return out;
}

namespace course_detail {
namespace fs = std::filesystem;

std::vector<uint32_t> sharing(const Mesh& m) {
  std::vector<uint32_t> share(m.positions.size());
  for (size_t i = 0; i < share.size(); ++i) share[i] = uint32_t(i);
  if (m.normals.size() != m.positions.size()) return share;
  std::map<std::array<uint32_t, 6>, uint32_t> first;
  for (size_t i = 0; i < share.size(); ++i) {
    std::array<uint32_t, 6> key;
    std::memcpy(key.data(), &m.positions[i], 12);
    std::memcpy(key.data() + 3, &m.normals[i], 12);
    share[i] = first.emplace(key, uint32_t(i)).first->second;
  }
  return share;
}

float normal_deviation(const Mesh& m, const std::vector<vec3>& course) {
  if (m.normals.size() != m.positions.size()) return 0.f;
  std::vector<uint8_t> used(m.positions.size(), 0);
  for (uint32_t i : m.indices) used[i] = 1;
  double worst = 0.0;
  for (size_t i = 0; i < m.positions.size(); ++i) {
    if (!used[i] || glm::length(m.normals[i]) == 0.f) continue;
    // atan2 of |a x b| and a . b: accurate for small angles, where acos is not.
    glm::dvec3 a = glm::normalize(glm::dvec3(m.normals[i])), b(course[i]);
    worst = std::max(worst, std::atan2(glm::length(glm::cross(a, b)), glm::dot(a, b)) * 180.0 / std::numbers::pi);
  }
  return float(worst);
}

// The OBJ file of one part of a mesh (faces of material `part`, or all when
// invalid), uvs transformed by material `uv_material`'s transform if any.
std::string CourseWriter::mesh_file(int mi, int part, int uv_material) {
  const Mesh& m = s_.meshes.at(size_t(mi));
  const UvTransform* t = nullptr;
  if (uv_material >= 0 && size_t(uv_material) < s_.materials.size() &&
      !s_.materials[size_t(uv_material)].uv_transform.is_identity() && !m.uvs.empty() &&
      s_.materials[size_t(uv_material)].diffuse_texture != invalid)
    t = &s_.materials[size_t(uv_material)].uv_transform;
  auto key = std::make_tuple(mi, part, t ? uv_material : invalid);
  auto it = mesh_files_.find(key);
  if (it != mesh_files_.end()) return it->second;
  if (t) baked_uvs_.insert(s_.materials[size_t(uv_material)].name);

  // The faces of this part.
  Mesh sub;
  sub.positions = m.positions;
  sub.normals = m.normals;
  if (part == invalid || m.face_materials.empty()) {
    sub.indices = m.indices;
  } else {
    for (size_t f = 0; f < m.triangle_count(); ++f)
      if (m.face_materials[f] == part)
        sub.indices.insert(sub.indices.end(), m.indices.begin() + long(3 * f), m.indices.begin() + long(3 * f + 3));
  }
  for (uint32_t i : sub.indices)
    if (i >= m.positions.size()) throw Error(context_.path + ": mesh '" + m.name + "' has an index out of range");
  const bool has_normals = m.normals.size() == m.positions.size();
  const bool has_uvs = m.uvs.size() == m.positions.size();
  std::vector<uint32_t> share = sharing(m);

  std::ostringstream o, uvs;
  std::vector<int64_t> vindex(m.positions.size(), -1);
  std::map<std::pair<uint32_t, uint32_t>, uint32_t> uv_index;
  uint32_t nv = 0, nt = 0;
  std::ostringstream faces;
  for (size_t c = 0; c < sub.indices.size(); ++c) {
    uint32_t i = sub.indices[c];
    uint32_t vi;
    if (has_normals) {
      uint32_t rep = share[i];
      if (vindex[rep] < 0) {
        vindex[rep] = nv++;
        o << "v " << format_vec3(m.positions[rep]) << "\n";
      }
      vi = uint32_t(vindex[rep]);
    } else {
      vi = nv++;  // unshared: the course gives each face its own normal
      o << "v " << format_vec3(m.positions[i]) << "\n";
    }
    uint32_t ti = 0;
    if (has_uvs) {
      vec2 uv = t ? t->apply(m.uvs[i]) : m.uvs[i];
      std::pair<uint32_t, uint32_t> k;
      std::memcpy(&k.first, &uv.x, 4);
      std::memcpy(&k.second, &uv.y, 4);
      auto [u, inserted] = uv_index.emplace(k, nt);
      if (inserted) {
        ++nt;
        uvs << "vt " << format_float(uv.x) << " " << format_float(uv.y) << "\n";
      }
      ti = u->second;
    }
    if (c % 3 == 0) faces << "f";
    faces << " " << (vi + 1);
    if (has_uvs) faces << "/" << (ti + 1);
    if (c % 3 == 2) faces << "\n";
  }
  o << uvs.str() << faces.str();

  // How far the course's own normals will be from the source's.
  if (has_normals) {
    float dev = normal_deviation(sub, course_normals(sub, share, dialect_));
    if (dev > 0.01f) {
      normal_deviation_ = std::max(normal_deviation_, dev);
      normals_changed_.insert(m.name);
    }
  }
  // Equal meshes (e.g. one mesh read back from glTF as a copy per material) share a file.
  std::string text = o.str();
  if (auto same = mesh_texts_.find(text); same != mesh_texts_.end()) {
    mesh_files_[key] = same->second;
    return same->second;
  }
  std::string base = fs::path(m.name.empty() ? "mesh" : m.name).stem().string();
  if (part != invalid && !m.face_materials.empty()) {
    base += '_';
    base += std::to_string(part);  // not "_" + ...: GCC 12 warns there wrongly (-Wrestrict)
  }
  std::string file = unique_file(safe_file_name(context_.stem + "_" + base), ".obj");
  stored_triangles_ += sub.indices.size() / 3;
  context_.out.add(context_.out.side_path(file), text);
  file = context_.out.side_reference(file);
  mesh_files_[key] = file;
  mesh_texts_.emplace(std::move(text), file);
  return file;
}

}  // namespace course_detail
}  // namespace rayform
