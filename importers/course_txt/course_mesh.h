// A TriangleMesh of the course format: geometry from the OBJ file, `vn` lines
// ignored, and smooth vertex normals made by the dialect's rule: the sum over
// the faces around a vertex of their face normals, area-weighted (2012, raw
// cross products) or unit (2019), then normalised. Texture coordinates are
// per corner, so vertices are split where one position has several uvs.
#pragma once

#include "course_txt/course_reader.h"

namespace rayform {

// Throws rayform::Error naming the file.
Mesh read_course_mesh(const std::string& path, CourseDialect dialect);

}  // namespace rayform
