#include "rayform/importers/course_txt/course_mesh.h"

#include "rayform/importers/obj/obj_geometry.h"
#include "rayform/importers/obj/obj_vertex_weld.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

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
  // Vertices split by (position, uv) pair, numbered in the order the pairs
  // are first met in corner order (obj_vertex_weld.h).
  obj::WeldedVertices welded = obj::weld_vertices(g.positions.size(), g.corners.size(), [&](size_t c) {
    return obj::CornerKey{g.corners[c].position, g.corners[c].uv, -1};
  });
  const size_t vertices = welded.first_corner.size();
  m.positions.resize(vertices);
  if (!flat) m.normals.resize(vertices);
  m.uvs.resize(vertices);
  tbb::parallel_for(tbb::blocked_range<size_t>(0, vertices, 4096), [&](const tbb::blocked_range<size_t>& r) {
    for (size_t v = r.begin(); v < r.end(); ++v) {
      const ObjGeometry::Corner& c = g.corners[welded.first_corner[v]];
      m.positions[v] = g.positions[size_t(c.position)];
      if (!flat) m.normals[v] = position_normals[size_t(c.position)];
      m.uvs[v] = c.uv >= 0 ? g.uvs[size_t(c.uv)] : vec2(0.f);
    }
  });
  m.indices = std::move(welded.corner_vertex);
  return m;
}

}  // namespace rayform
