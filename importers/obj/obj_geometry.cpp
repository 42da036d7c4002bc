#include "rayform/importers/obj/obj_geometry.h"

#include "rayform/base/error.h"

#include <tiny_obj_loader.h>

#include <cmath>
#include <fstream>

namespace rayform {

ObjGeometry read_obj_geometry(const std::string& path) {
  {
    std::ifstream probe(path);
    if (!probe) throw Error(path + ": cannot open OBJ file");
  }
  tinyobj::ObjReaderConfig config;
  config.triangulate = true;
  config.vertex_color = false;
  config.mtl_search_path = "";  // geometry only: materials are not needed here
  tinyobj::ObjReader reader;
  if (!reader.ParseFromFile(path, config)) {
    std::string e = reader.Error();
    while (!e.empty() && e.back() == '\n') e.pop_back();
    throw Error(path + ": cannot read OBJ: " + e);
  }
  const tinyobj::attrib_t& a = reader.GetAttrib();
  ObjGeometry g;
  g.positions.resize(a.vertices.size() / 3);
  for (size_t i = 0; i < g.positions.size(); ++i) {
    g.positions[i] = vec3(a.vertices[3 * i], a.vertices[3 * i + 1], a.vertices[3 * i + 2]);
    if (!is_finite(g.positions[i]))
      throw Error(path + ": vertex " + std::to_string(i + 1) + " has a non-finite coordinate");
  }
  g.normals.resize(a.normals.size() / 3);
  for (size_t i = 0; i < g.normals.size(); ++i)
    g.normals[i] = vec3(a.normals[3 * i], a.normals[3 * i + 1], a.normals[3 * i + 2]);
  g.uvs.resize(a.texcoords.size() / 2);
  for (size_t i = 0; i < g.uvs.size(); ++i) g.uvs[i] = vec2(a.texcoords[2 * i], a.texcoords[2 * i + 1]);

  auto check = [&](int index, size_t count, const char* what) {
    if (index >= int(count) || index < -1)
      throw Error(path + ": face refers to " + what + " " + std::to_string(index + 1) + " but the file has " +
                  std::to_string(count));
  };
  for (const tinyobj::shape_t& shape : reader.GetShapes()) {
    size_t offset = 0;
    for (unsigned char fv : shape.mesh.num_face_vertices) {
      if (fv == 3) {
        for (int k = 0; k < 3; ++k) {
          const tinyobj::index_t& ix = shape.mesh.indices[offset + k];
          check(ix.vertex_index, g.positions.size(), "vertex");
          check(ix.normal_index, g.normals.size(), "normal");
          check(ix.texcoord_index, g.uvs.size(), "texture coordinate");
          if (ix.vertex_index < 0) throw Error(path + ": face corner without a vertex index");
          g.corners.push_back({ix.vertex_index, ix.normal_index, ix.texcoord_index});
        }
      }
      offset += fv;
    }
  }
  if (g.corners.empty()) throw Error(path + ": OBJ file has no triangles");
  std::string w = reader.Warning();
  if (!w.empty()) g.warnings.push_back(path + ": " + w);
  return g;
}

}  // namespace rayform
