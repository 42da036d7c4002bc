// Raw OBJ geometry read through tinyobjloader: positions, texture coordinates
// and, per triangle corner, the indices into them (polygons fan-triangulated).
// Importers turn it into a Mesh under their own rules (the course computes its
// own normals; the asset importer keeps or generates them).
#pragma once

#include "rayform/math/math.h"

#include <string>
#include <vector>

namespace rayform {

struct ObjGeometry {
  std::vector<vec3> positions;
  std::vector<vec3> normals;
  std::vector<vec2> uvs;
  struct Corner {
    int position = -1, normal = -1, uv = -1;  // -1: absent
  };
  std::vector<Corner> corners;  // three per triangle
  std::vector<std::string> warnings;
};

// Throws rayform::Error naming the file (and the line, where tinyobjloader
// reports one) when the file cannot be read, has no faces, or an index is out
// of range.
ObjGeometry read_obj_geometry(const std::string& path);

}  // namespace rayform
