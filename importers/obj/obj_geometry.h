// Raw OBJ geometry read through tinyobjloader: positions, texture coordinates
// and, per triangle corner, the indices into them (polygons fan-triangulated).
// Importers turn it into a Mesh under their own rules (the course computes its
// own normals; the asset importer keeps or generates them).
//
// A large text is parsed in chunks at once (obj_parallel_parse.h, as
// read_obj_scene parses it) where that gives exactly the one-piece parse;
// the result is the same either way, warnings included.
#pragma once

#include "rayform/math/math.h"

#include <cstddef>
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

// How read_obj_geometry parses the text: 0 chooses (in chunks at once for a
// large file when more than one thread may run, as read_obj_scene chooses);
// `serial` in one piece; any other number forces chunks of about that many
// bytes (tests: the result is the same).
struct ObjGeometryOptions {
  static constexpr size_t serial = ~size_t(0);
  size_t parse_chunk_bytes = 0;
};

// Throws rayform::Error naming the file (and the line, where tinyobjloader
// reports one) when the file cannot be read, has no faces, or an index is out
// of range. MTL files it names are looked for beside it (tinyobjloader's
// rule), for their warnings only.
ObjGeometry read_obj_geometry(const std::string& path, const ObjGeometryOptions& options = {});

}  // namespace rayform
