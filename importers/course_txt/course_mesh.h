// A TriangleMesh of the course format: geometry from the OBJ file, `vn` lines
// ignored, and smooth vertex normals made by the dialect's rule: the sum over
// the faces around a vertex of their face normals, area-weighted (2012, raw
// cross products) or unit (2019), then normalised. Texture coordinates are
// per corner, so vertices are split where one position has several uvs. The
// a5 dialect shades meshes of at most 120 vertices flat.
#pragma once

#include "rayform/importers/course_txt/course_reader.h"

#include <cstdint>
#include <vector>

namespace rayform {

// The course's vertex-normal rule, per position: the sum over the faces that
// use a position (three entries of `corners` a face, each a position index)
// of their face normals, raw cross products (2012) or unit ones (2019, faces
// of zero area skipped), normalised; zero for a position no face uses.
std::vector<vec3> course_position_normals(const std::vector<vec3>& positions, const std::vector<uint32_t>& corners,
                                          CourseDialect dialect);

// a5: a mesh file of at most this many vertices is shaded with flat face
// normals, (v1 - v0) x (v2 - v0); a larger one as 2012 (area-weighted).
inline constexpr size_t course_a5_flat_mesh_vertices = 120;

// Throws rayform::Error naming the file; a5 reads as 2012 but for the flat
// normals of small meshes (course_a5_flat_mesh_vertices).
Mesh read_course_mesh(const std::string& path, CourseDialect dialect);

}  // namespace rayform
