#include "rayform/importers/obj/obj_geometry.h"

#include "rayform/importers/file_bytes.h"
#include "rayform/importers/obj/obj_parallel_parse.h"
#include "rayform/importers/obj/text_stream_buffer.h"
#include "rayform/base/error.h"

#include <tbb/global_control.h>
#include <tiny_obj_loader.h>

#include <istream>
#include <memory>

namespace rayform {
namespace {

// As read_obj_scene chooses (obj_reader.cpp): a text under 1 MiB, or one
// thread, in one piece; else about 16 chunks per thread.
constexpr size_t min_parallel_bytes = size_t(1) << 20;
constexpr size_t chunks_per_thread = 16;

// Where tinyobj::ObjReader::ParseFromFile (the one-piece parse this reader
// made before the chunked one) looks for MTL files: the file's folder, as
// LoadObj(filename) spells it ("" for a bare file name: as written).
std::string mtl_base_dir(const std::string& path) {
  const size_t slash = path.find_last_of("/\\");
  if (slash == std::string::npos || slash == 0) return {};
  return path.substr(0, slash) + '/';
}

}  // namespace

ObjGeometry read_obj_geometry(const std::string& path, const ObjGeometryOptions& options) {
  const FileBytes file(path, "OBJ file");
  const std::string_view text = file.view();
  const std::string base_dir = mtl_base_dir(path);
  const MaterialReaderFactory readers = [&] { return std::make_unique<tinyobj::MaterialFileReader>(base_dir); };

  size_t chunk = options.parse_chunk_bytes;
  if (chunk == 0) {
    const size_t threads = tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism);
    chunk = threads > 1 && text.size() >= min_parallel_bytes ? text.size() / (chunks_per_thread * threads) + 1 : 0;
  }
  ObjParse parsed;
  // The chunks' warnings are those of the whole text only as a set (a chunk
  // repeats an unknown material's warning): any warning, and the text is
  // parsed in one piece, for the very warnings of that parse.
  const bool chunked = chunk != 0 && chunk != ObjGeometryOptions::serial &&
                       parse_obj_chunked(text, readers, chunk, &parsed) && parsed.warn.empty();
  if (!chunked) {
    parsed = ObjParse{};
    TextStreamBuffer buffer(text);
    std::istream in(&buffer);
    const std::unique_ptr<tinyobj::MaterialReader> reader = readers();
    std::vector<tinyobj::material_t> materials;
    std::string e;
    if (!tinyobj::LoadObj(&parsed.attrib, &parsed.shapes, &materials, &parsed.warn, &e, &in, reader.get(),
                          /*triangulate*/ true, /*default_vcols_fallback*/ false)) {
      while (!e.empty() && e.back() == '\n') e.pop_back();
      throw Error(path + ": cannot read OBJ: " + e);
    }
  }

  const tinyobj::attrib_t& a = parsed.attrib;
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
  size_t corners = 0;
  for (const tinyobj::shape_t& shape : parsed.shapes) corners += shape.mesh.indices.size();
  g.corners.reserve(corners);
  for (const tinyobj::shape_t& shape : parsed.shapes) {
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
  if (!parsed.warn.empty()) g.warnings.push_back(path + ": " + parsed.warn);
  return g;
}

}  // namespace rayform
