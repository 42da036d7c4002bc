#include "rayform/importers/obj/obj_geometry.h"

#include "rayform/importers/file_bytes.h"
#include "rayform/importers/obj/obj_parallel_parse.h"
#include "rayform/importers/obj/text_stream_buffer.h"
#include "rayform/base/error.h"

#include <tbb/blocked_range.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>
#include <tiny_obj_loader.h>

#include <algorithm>
#include <istream>
#include <memory>

namespace rayform {
namespace {

// As read_obj_scene chooses (obj_reader.cpp): a text under 1 MiB by one
// LoadObj; else one chunk on one thread, about 16 chunks per thread on more.
constexpr size_t min_parallel_bytes = size_t(1) << 20;
constexpr size_t chunks_per_thread = 16;
// Elements per block of the copies and checks after the parse.
constexpr size_t grain = size_t(1) << 14;

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
    chunk = text.size() < min_parallel_bytes ? 0
            : threads > 1                    ? text.size() / (chunks_per_thread * threads) + 1
                                             : text.size();
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
  g.normals.resize(a.normals.size() / 3);
  g.uvs.resize(a.texcoords.size() / 2);
  // The arrays copied, and the first vertex with a non-finite coordinate
  // found, blocks at once.
  const size_t nv = g.positions.size();
  const size_t bad_vertex = tbb::parallel_reduce(
      tbb::blocked_range<size_t>(0, nv, grain), nv,
      [&](const tbb::blocked_range<size_t>& r, size_t first) {
        for (size_t i = r.begin(); i < r.end(); ++i) {
          g.positions[i] = vec3(a.vertices[3 * i], a.vertices[3 * i + 1], a.vertices[3 * i + 2]);
          if (i < first && !is_finite(g.positions[i])) first = i;
        }
        return first;
      },
      [](size_t x, size_t y) { return std::min(x, y); });
  if (bad_vertex < nv)
    throw Error(path + ": vertex " + std::to_string(bad_vertex + 1) + " has a non-finite coordinate");
  tbb::parallel_for(tbb::blocked_range<size_t>(0, g.normals.size(), grain), [&](const tbb::blocked_range<size_t>& r) {
    for (size_t i = r.begin(); i < r.end(); ++i)
      g.normals[i] = vec3(a.normals[3 * i], a.normals[3 * i + 1], a.normals[3 * i + 2]);
  });
  tbb::parallel_for(tbb::blocked_range<size_t>(0, g.uvs.size(), grain), [&](const tbb::blocked_range<size_t>& r) {
    for (size_t i = r.begin(); i < r.end(); ++i) g.uvs[i] = vec2(a.texcoords[2 * i], a.texcoords[2 * i + 1]);
  });

  // The triangles' corners of every shape, in order (faces of another size,
  // which the triangulating parse does not leave, are skipped).
  std::vector<const tinyobj::index_t*> corner_of;  // where not every face is a triangle: each corner's index
  struct Run {
    const tinyobj::index_t* indices;  // all the shape's corners, or null: corner_of's from `from`
    size_t from, at, count;           // at: the first in g.corners
  };
  std::vector<Run> runs;
  size_t corners = 0;
  for (const tinyobj::shape_t& shape : parsed.shapes) {
    const tinyobj::mesh_t& m = shape.mesh;
    const bool triangles =
        std::all_of(m.num_face_vertices.begin(), m.num_face_vertices.end(), [](unsigned char fv) { return fv == 3; });
    if (triangles && m.indices.size() == 3 * m.num_face_vertices.size()) {
      runs.push_back({m.indices.data(), 0, corners, m.indices.size()});
      corners += m.indices.size();
      continue;
    }
    const size_t before = corner_of.size();
    size_t offset = 0;
    for (unsigned char fv : m.num_face_vertices) {
      if (fv == 3)
        for (size_t k = 0; k < 3; ++k) corner_of.push_back(&m.indices[offset + k]);
      offset += fv;
    }
    runs.push_back({nullptr, before, corners, corner_of.size() - before});
    corners += corner_of.size() - before;
  }
  // Each run's corners checked and copied, blocks at once; the first corner
  // that fails a check, in order, is the one reported.
  auto ok = [&](const tinyobj::index_t& ix) {
    return ix.vertex_index >= 0 && ix.vertex_index < int(nv) && ix.normal_index >= -1 &&
           ix.normal_index < int(g.normals.size()) && ix.texcoord_index >= -1 && ix.texcoord_index < int(g.uvs.size());
  };
  g.corners.resize(corners);
  for (const Run& run : runs) {
    auto index = [&](size_t c) -> const tinyobj::index_t& {
      return run.indices ? run.indices[c] : *corner_of[run.from + c];
    };
    ObjGeometry::Corner* to = g.corners.data() + run.at;
    const size_t bad = tbb::parallel_reduce(
        tbb::blocked_range<size_t>(0, run.count, grain), run.count,
        [&](const tbb::blocked_range<size_t>& r, size_t first) {
          for (size_t c = r.begin(); c < r.end(); ++c) {
            const tinyobj::index_t& ix = index(c);
            to[c] = {ix.vertex_index, ix.normal_index, ix.texcoord_index};
            if (c < first && !ok(ix)) first = c;
          }
          return first;
        },
        [](size_t x, size_t y) { return std::min(x, y); });
    if (bad == run.count) continue;
    const tinyobj::index_t& ix = index(bad);
    auto check = [&](int i, size_t count, const char* what) {
      if (i >= int(count) || i < -1)
        throw Error(path + ": face refers to " + what + " " + std::to_string(i + 1) + " but the file has " +
                    std::to_string(count));
    };
    check(ix.vertex_index, nv, "vertex");
    check(ix.normal_index, g.normals.size(), "normal");
    check(ix.texcoord_index, g.uvs.size(), "texture coordinate");
    throw Error(path + ": face corner without a vertex index");
  }
  if (g.corners.empty()) throw Error(path + ": OBJ file has no triangles");
  if (!parsed.warn.empty()) g.warnings.push_back(path + ": " + parsed.warn);
  return g;
}

}  // namespace rayform
