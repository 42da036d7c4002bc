#include "course_txt/course_mesh.h"

#include "obj/obj_geometry.h"

#include <map>

namespace rayform {

Mesh read_course_mesh(const std::string& path, CourseDialect dialect) {
  ObjGeometry g = read_obj_geometry(path);
  // Normals per position index.
  std::vector<vec3> position_normals(g.positions.size(), vec3(0.f));
  for (size_t c = 0; c < g.corners.size(); c += 3) {
    int i0 = g.corners[c].position, i1 = g.corners[c + 1].position, i2 = g.corners[c + 2].position;
    vec3 n = glm::cross(g.positions[i1] - g.positions[i0], g.positions[i2] - g.positions[i0]);
    if (dialect == CourseDialect::v2019) {
      float len = glm::length(n);
      if (!(len > 0.f)) continue;  // a zero-area face has no direction to add
      n /= len;
    }
    position_normals[i0] += n;
    position_normals[i1] += n;
    position_normals[i2] += n;
  }
  for (vec3& n : position_normals) {
    float len = glm::length(n);
    n = len > 0.f ? n / len : vec3(0.f);
  }

  Mesh m;
  m.source_path = path;
  bool has_uv = false;
  for (const auto& c : g.corners) has_uv |= c.uv >= 0;
  if (!has_uv) {
    m.positions = g.positions;
    m.normals = position_normals;
    for (const auto& c : g.corners) m.indices.push_back(uint32_t(c.position));
    return m;
  }
  // Split vertices by (position, uv) pair.
  std::map<std::pair<int, int>, uint32_t> split;
  for (const auto& c : g.corners) {
    auto [it, inserted] = split.try_emplace({c.position, c.uv}, uint32_t(m.positions.size()));
    if (inserted) {
      m.positions.push_back(g.positions[c.position]);
      m.normals.push_back(position_normals[c.position]);
      m.uvs.push_back(c.uv >= 0 ? g.uvs[c.uv] : vec2(0.f));
    }
    m.indices.push_back(it->second);
  }
  return m;
}

}  // namespace rayform
