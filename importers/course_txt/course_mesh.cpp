#include "rayform/importers/course_txt/course_mesh.h"

#include "rayform/importers/obj/obj_geometry.h"
#include "rayform/importers/obj/obj_vertex_weld.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>

namespace rayform {
namespace {

// Elements per block of the loops run at once.
constexpr size_t grain = size_t(1) << 14;

}  // namespace

std::vector<vec3> course_position_normals(const std::vector<vec3>& positions, const std::vector<uint32_t>& corners,
                                          CourseDialect dialect) {
  // Each face's normal, blocks at once (the operations of one loop, so the
  // same bits); a zero-area face of 2019 gives +0, whose sum leaves every
  // position's as it is (a sum that starts at +0 is never -0).
  const size_t faces = corners.size() / 3;
  std::vector<vec3> face(faces);
  tbb::parallel_for(tbb::blocked_range<size_t>(0, faces, grain), [&](const tbb::blocked_range<size_t>& r) {
    for (size_t f = r.begin(); f < r.end(); ++f) {
      const uint32_t i0 = corners[3 * f], i1 = corners[3 * f + 1], i2 = corners[3 * f + 2];
      vec3 n = glm::cross(positions[i1] - positions[i0], positions[i2] - positions[i0]);
      if (dialect == CourseDialect::v2019) {
        const float len = glm::length(n);
        n = len > 0.f ? n / len : vec3(0.f);  // a zero-area face has no direction to add
      }
      face[f] = n;
    }
  });
  // Summed per position in corner order, as one loop over the faces sums them.
  std::vector<vec3> sum(positions.size(), vec3(0.f));
  for (size_t f = 0; f < faces; ++f) {
    sum[corners[3 * f]] += face[f];
    sum[corners[3 * f + 1]] += face[f];
    sum[corners[3 * f + 2]] += face[f];
  }
  tbb::parallel_for(tbb::blocked_range<size_t>(0, sum.size(), grain), [&](const tbb::blocked_range<size_t>& r) {
    for (size_t i = r.begin(); i < r.end(); ++i) {
      const float len = glm::length(sum[i]);
      sum[i] = len > 0.f ? sum[i] / len : vec3(0.f);
    }
  });
  return sum;
}

Mesh read_course_mesh(const std::string& path, CourseDialect dialect) {
  ObjGeometry g = read_obj_geometry(path);
  std::vector<uint32_t> corners(g.corners.size());
  tbb::parallel_for(tbb::blocked_range<size_t>(0, corners.size(), grain), [&](const tbb::blocked_range<size_t>& r) {
    for (size_t c = r.begin(); c < r.end(); ++c) corners[c] = uint32_t(g.corners[c].position);
  });
  std::vector<vec3> position_normals = course_position_normals(g.positions, corners, dialect);

  Mesh m;
  m.source_path = path;
  // a5: a small mesh file is shaded with flat face normals (Mesh::normals empty).
  const bool flat = dialect == CourseDialect::a5 && g.positions.size() <= course_a5_flat_mesh_vertices;
  const bool has_uv = std::any_of(g.corners.begin(), g.corners.end(), [](const auto& c) { return c.uv >= 0; });
  if (!has_uv) {
    m.positions = std::move(g.positions);
    if (!flat) m.normals = std::move(position_normals);
    m.indices = std::move(corners);
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
