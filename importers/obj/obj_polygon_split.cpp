#include "rayform/importers/obj/obj_polygon_split.h"

#include "rayform/importers/obj/text_stream_buffer.h"

#include <istream>
#include <string>

namespace rayform {
namespace {

// |q - p|^2 of two vertices, summed x + y + z in float as tinyobjloader does.
tinyobj::real_t squared_distance(const std::vector<tinyobj::real_t>& v, int p, int q) {
  const tinyobj::real_t dx = v[3 * size_t(q)] - v[3 * size_t(p)];
  const tinyobj::real_t dy = v[3 * size_t(q) + 1] - v[3 * size_t(p) + 1];
  const tinyobj::real_t dz = v[3 * size_t(q) + 2] - v[3 * size_t(p) + 2];
  return dx * dx + dy * dy + dz * dz;
}

// The triangles of a polygon of five or more corners, as corner numbers
// (0-based, three per triangle), from tinyobjloader's own split of it.
bool split_large_polygon(const tinyobj::index_t* corners, size_t n, const VertexLineText& vertex_line,
                         std::vector<int>* triangles) {
  std::string text;
  for (size_t k = 0; k < n; ++k) text.append(vertex_line(corners[k].vertex_index)).append("\n");
  for (size_t k = 0; k < n; ++k) text.append("vt 0 0\n");
  text.append("f");
  for (size_t k = 1; k <= n; ++k) text.append(" ").append(std::to_string(k)).append("/").append(std::to_string(k));
  text.append("\n");
  TextStreamBuffer buffer(text);
  std::istream in(&buffer);
  tinyobj::attrib_t attrib;
  std::vector<tinyobj::shape_t> shapes;
  std::vector<tinyobj::material_t> materials;
  std::string warn, err;
  if (!tinyobj::LoadObj(&attrib, &shapes, &materials, &warn, &err, &in, nullptr, /*triangulate*/ true,
                        /*default_vcols_fallback*/ false) ||
      !warn.empty() || !err.empty() || attrib.vertices.size() != 3 * n || shapes.size() > 1)
    return false;
  triangles->clear();
  if (shapes.empty()) return true;  // every corner clipped away: no triangle
  for (const tinyobj::index_t& ix : shapes[0].mesh.indices) {
    if (ix.texcoord_index < 0 || size_t(ix.texcoord_index) >= n) return false;
    triangles->push_back(ix.texcoord_index);
  }
  return triangles->size() % 3 == 0;
}

}  // namespace

bool split_polygons_like_loadobj(tinyobj::mesh_t* mesh, const std::vector<tinyobj::real_t>& positions,
                                 const VertexLineText& vertex_line) {
  tinyobj::mesh_t& m = *mesh;
  const size_t faces = m.num_face_vertices.size();
  bool any = false;
  for (size_t f = 0; f < faces && !any; ++f) any = m.num_face_vertices[f] > 3;
  if (!any) return true;
  tinyobj::mesh_t out;
  out.indices.reserve(m.indices.size() + m.indices.size() / 2);
  out.num_face_vertices.reserve(faces * 2);
  out.material_ids.reserve(faces * 2);
  out.smoothing_group_ids.reserve(faces * 2);
  const bool smoothing = m.smoothing_group_ids.size() == faces;
  auto add = [&](size_t f, const tinyobj::index_t& a, const tinyobj::index_t& b, const tinyobj::index_t& c) {
    out.indices.insert(out.indices.end(), {a, b, c});
    out.num_face_vertices.push_back(3);
    out.material_ids.push_back(m.material_ids[f]);
    if (smoothing) out.smoothing_group_ids.push_back(m.smoothing_group_ids[f]);
  };
  std::vector<int> triangles;
  size_t at = 0;
  for (size_t f = 0; f < faces; ++f) {
    const size_t n = m.num_face_vertices[f];
    const tinyobj::index_t* c = &m.indices[at];
    at += n;
    if (n == 3) {
      add(f, c[0], c[1], c[2]);
    } else if (n == 4) {
      if (squared_distance(positions, c[0].vertex_index, c[2].vertex_index) <
          squared_distance(positions, c[1].vertex_index, c[3].vertex_index)) {
        add(f, c[0], c[1], c[2]);
        add(f, c[0], c[2], c[3]);
      } else {
        add(f, c[0], c[1], c[3]);
        add(f, c[1], c[2], c[3]);
      }
    } else {
      if (!split_large_polygon(c, n, vertex_line, &triangles)) return false;
      for (size_t t = 0; t < triangles.size(); t += 3)
        add(f, c[triangles[t]], c[triangles[t + 1]], c[triangles[t + 2]]);
    }
  }
  out.tags = std::move(m.tags);
  m = std::move(out);
  return true;
}

}  // namespace rayform
