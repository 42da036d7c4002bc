#include "rayform/importers/course_txt/course_mesh.h"

#include "rayform/importers/obj/obj_geometry.h"

#include <map>

namespace rayform {

std::vector<vec3> course_position_normals(const std::vector<vec3>& positions, const std::vector<uint32_t>& corners,
                                          CourseDialect dialect) {
  std::vector<vec3> sum(positions.size(), vec3(0.f));
  for (size_t c = 0; c + 2 < corners.size(); c += 3) {
    const uint32_t i0 = corners[c], i1 = corners[c + 1], i2 = corners[c + 2];
    vec3 n = glm::cross(positions[i1] - positions[i0], positions[i2] - positions[i0]);
    if (dialect == CourseDialect::v2019) {
      const float len = glm::length(n);
      if (!(len > 0.f)) continue;  // a zero-area face has no direction to add
      n /= len;
    }
    sum[i0] += n;
    sum[i1] += n;
    sum[i2] += n;
  }
  for (vec3& n : sum) {
    const float len = glm::length(n);
    n = len > 0.f ? n / len : vec3(0.f);
  }
  return sum;
}

Mesh read_course_mesh(const std::string& path, CourseDialect dialect) {
  ObjGeometry g = read_obj_geometry(path);
  std::vector<uint32_t> corners;
  corners.reserve(g.corners.size());
  for (const auto& c : g.corners) corners.push_back(uint32_t(c.position));
  const std::vector<vec3> position_normals = course_position_normals(g.positions, corners, dialect);

  Mesh m;
  m.source_path = path;
  // a5: a small mesh file is shaded with flat face normals (Mesh::normals empty).
  const bool flat = dialect == CourseDialect::a5 && g.positions.size() <= course_a5_flat_mesh_vertices;
  bool has_uv = false;
  for (const auto& c : g.corners) has_uv |= c.uv >= 0;
  if (!has_uv) {
    m.positions = g.positions;
    if (!flat) m.normals = position_normals;
    for (const auto& c : g.corners) m.indices.push_back(uint32_t(c.position));
    return m;
  }
  // Split vertices by (position, uv) pair.
  std::map<std::pair<int, int>, uint32_t> split;
  for (const auto& c : g.corners) {
    auto [it, inserted] = split.try_emplace({c.position, c.uv}, uint32_t(m.positions.size()));
    if (inserted) {
      m.positions.push_back(g.positions[c.position]);
      if (!flat) m.normals.push_back(position_normals[c.position]);
      m.uvs.push_back(c.uv >= 0 ? g.uvs[c.uv] : vec2(0.f));
    }
    m.indices.push_back(it->second);
  }
  return m;
}

}  // namespace rayform
