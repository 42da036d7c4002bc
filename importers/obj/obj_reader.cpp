#include "rayform/importers/obj/obj_reader.h"

#include "rayform/importers/file_bytes.h"
#include "rayform/importers/obj/mtl_library.h"
#include "rayform/importers/obj/obj_bad_index.h"
#include "rayform/importers/obj/obj_parallel_parse.h"
#include "rayform/importers/obj/obj_materials.h"
#include "rayform/importers/obj/obj_side_files.h"
#include "rayform/importers/obj/obj_smooth_normals.h"
#include "rayform/importers/obj/obj_text_bounds.h"
#include "rayform/importers/obj/obj_vertex_weld.h"
#include "rayform/importers/obj/text_stream_buffer.h"

#include "rayform/base/error.h"
#include "rayform/base/populate_pages.h"

#include <tbb/blocked_range.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>
#include <tiny_obj_loader.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <set>
#include <sstream>
#include <string_view>

namespace rayform {
namespace fs = std::filesystem;
namespace {

using obj::BadIndex;
using obj::find_bad_index;
using obj::MtlLibrary;
using obj::PreloadedMaterials;
using obj::trim;

// Smaller files are parsed by one LoadObj: the scan and join around a
// chunked parse do not pay there. Larger ones go through the chunked parse
// on one thread too, as one chunk (nothing to join): a plain chunk parses
// faster than LoadObj (obj_plain_chunk.h).
constexpr size_t min_parallel_bytes = size_t(1) << 20;
// Chunks of a parallel parse per thread: lines of faces parse slower than
// lines of vertices, so equal shares of the bytes are unequal shares of the
// work; cutting each thread's share into several chunks lets a thread that
// is done take the next chunk and evens the work out, while each chunk adds
// its own LoadObj call and join (docs/performance.md, the parallel parse).
constexpr size_t chunks_per_thread = 16;
// A parse shared among processes (ObjReadOptions::share) cuts the text into
// this many chunks per process: a number that does not depend on a
// process's threads (all must cut alike), enough for 8 threads each to take
// 4 chunks (balance), and small enough to cost nothing per chunk.
constexpr size_t shared_chunks_per_part = 32;

class ObjReader {
 public:
  ObjReader(const std::string& path, const ObjReadOptions& options, std::vector<std::string>* warnings)
      : path_(path), options_(options), warnings_(warnings), dir_(fs::path(path).parent_path()) {}

  Scene read() {
    file_ = FileBytes(path_, "OBJ file");
    obj::check_obj_text_bounds(file_, path_);
    text_ = file_.view();
    materials_.load_libraries(text_);

    ObjParse parsed = parse();
    const tinyobj::attrib_t& attrib = parsed.attrib;
    const std::vector<tinyobj::shape_t>& shapes = parsed.shapes;
    handle_tinyobj_warnings(parsed.warn);

    const size_t nv = attrib.vertices.size() / 3;
    const size_t nt = attrib.texcoords.size() / 2;
    const size_t nn = attrib.normals.size() / 3;
    // The first vertex with a non-finite coordinate, if any (blocks at once).
    const size_t bad_vertex = tbb::parallel_reduce(
        tbb::blocked_range<size_t>(0, nv, 1 << 14), nv,
        [&](const tbb::blocked_range<size_t>& r, size_t first) {
          for (size_t i = r.begin(); i < r.end() && i < first; ++i)
            if (!std::isfinite(attrib.vertices[3 * i]) || !std::isfinite(attrib.vertices[3 * i + 1]) ||
                !std::isfinite(attrib.vertices[3 * i + 2]))
              return i;
          return first;
        },
        [](size_t a, size_t b) { return std::min(a, b); });
    if (bad_vertex < nv)
      throw Error(path_ + ": vertex " + std::to_string(bad_vertex + 1) + " has a non-finite coordinate");

    // Check every corner; uv and normal indices that name nothing drop that
    // attribute for the whole file (with a warning), as other converters do.
    struct CornerCheck {
      bool positions_ok = true, uvs_ok = true, normals_ok = true;
    };
    CornerCheck check;
    for (const tinyobj::shape_t& s : shapes) {
      const std::vector<tinyobj::index_t>& corners = s.mesh.indices;
      const CornerCheck c = tbb::parallel_reduce(
          tbb::blocked_range<size_t>(0, corners.size(), 1 << 15), CornerCheck{},
          [&](const tbb::blocked_range<size_t>& r, CornerCheck acc) {
            for (size_t i = r.begin(); i < r.end(); ++i) {
              const tinyobj::index_t& ix = corners[i];
              acc.positions_ok &= ix.vertex_index >= 0 && size_t(ix.vertex_index) < nv;
              acc.uvs_ok &= ix.texcoord_index >= -1 && (ix.texcoord_index < 0 || size_t(ix.texcoord_index) < nt);
              acc.normals_ok &= ix.normal_index >= -1 && (ix.normal_index < 0 || size_t(ix.normal_index) < nn);
            }
            return acc;
          },
          [](CornerCheck a, const CornerCheck& b) {
            return CornerCheck{a.positions_ok && b.positions_ok, a.uvs_ok && b.uvs_ok, a.normals_ok && b.normals_ok};
          });
      if (!c.positions_ok) fail_bad_index(0, nv);
      check.uvs_ok &= c.uvs_ok;
      check.normals_ok &= c.normals_ok;
    }
    const bool uvs_ok = check.uvs_ok, normals_ok = check.normals_ok;
    if (!uvs_ok) warn_bad_index(1, nt, "texture coordinates");
    if (!normals_ok) warn_bad_index(2, nn, "normals");
    // Written normals of zero (or non-finite) length count as missing.
    normal_usable_.assign(nn, 1);
    size_t unusable = 0;
    for (size_t i = 0; i < nn; ++i) {
      float len = glm::length(vec3(attrib.normals[3 * i], attrib.normals[3 * i + 1], attrib.normals[3 * i + 2]));
      if (!(len > 0.f) || !std::isfinite(len)) {
        normal_usable_[i] = 0;
        ++unusable;
      }
    }
    if (unusable)
      warn(path_ + ": " + std::to_string(unusable) +
           " written normal(s) of zero length; generated normals are used there");

    has_colors_ = attrib.colors.size() == attrib.vertices.size() && nv > 0;
    if (has_colors_)
      has_colors_ = std::any_of(attrib.colors.begin(), attrib.colors.end(), [](float c) { return c != 1.f; });

    materials_.convert();

    Node root;
    root.kind = Node::Kind::group;
    root.name = fs::path(path_).stem().string();
    std::vector<int> children;
    size_t triangles = 0;
    for (const tinyobj::shape_t& s : shapes) {
      if (s.mesh.indices.empty()) {
        if (!s.lines.indices.empty() || !s.points.indices.empty())
          warn(path_ + ": '" + s.name + "' holds only lines or points, which are not rendered");
        continue;
      }
      int mesh = build_mesh(s, attrib, uvs_ok, normals_ok);
      if (mesh == invalid) continue;
      triangles += scene_.meshes[mesh].triangle_count();
      Node shape;
      shape.kind = Node::Kind::shape;
      shape.name = scene_.meshes[mesh].name;
      shape.shape_kind = ShapeKind::mesh;
      shape.shape = mesh;
      shape.material = mesh_node_material_;
      Node group;
      group.kind = Node::Kind::group;
      group.name = scene_.meshes[mesh].name;
      group.children = {add_node(std::move(shape))};
      children.push_back(add_node(std::move(group)));
    }
    if (triangles == 0) throw Error(path_ + ": OBJ file has no faces");
    root.children = std::move(children);
    scene_.root = add_node(std::move(root));
    scene_.source_path = path_;
    return std::move(scene_);
  }

 private:
  // The text through tinyobjloader: in chunks at once where that gives the
  // same (see obj_parallel_parse.h) and pays, else in one piece.
  ObjParse parse() {
    ObjParse parsed;
    MaterialReaderFactory readers = [&] { return std::make_unique<PreloadedMaterials>(materials_.library()); };
    const WorkShare* share = options_.share && options_.share->shared() ? options_.share : nullptr;
    size_t chunk = options_.parse_chunk_bytes;
    if (chunk == 0 && share) {
      // The same chunks on every part, whatever threads each has.
      chunk =
          text_.size() >= min_parallel_bytes ? text_.size() / (size_t(share->parts) * shared_chunks_per_part) + 1 : 0;
    } else if (chunk == 0) {
      const size_t threads = tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism);
      chunk = text_.size() < min_parallel_bytes ? 0
              : threads > 1                     ? text_.size() / (chunks_per_thread * threads) + 1
                                                : text_.size();
    }
    if (chunk != 0 && chunk != ObjReadOptions::serial && parse_obj_chunked(text_, readers, chunk, &parsed, share))
      return parsed;
    parsed = ObjParse{};
    std::vector<tinyobj::material_t> materials;
    std::string err;
    TextStreamBuffer buffer(text_);
    std::istream in(&buffer);
    std::unique_ptr<tinyobj::MaterialReader> reader = readers();
    bool ok = tinyobj::LoadObj(&parsed.attrib, &parsed.shapes, &materials, &parsed.warn, &err, &in, reader.get(),
                               /*triangulate*/ true, /*default_vcols_fallback*/ false);
    if (!ok) fail_from_tinyobj(err);
    return parsed;
  }

  void warn(std::string w) {
    if (warnings_ && seen_warnings_.insert(w).second) warnings_->push_back(std::move(w));
  }

  int add_node(Node n) {
    scene_.nodes.push_back(std::move(n));
    return int(scene_.nodes.size()) - 1;
  }

  // ---- geometry ----------------------------------------------------------

  // A shape's triangles as tinyobjloader gives them: after its triangulation
  // every face is one (faces of another size are skipped, defensively).
  struct ShapeTriangles {
    const std::vector<tinyobj::index_t>& idx;
    std::vector<size_t> face_start;        // per face: its first corner in idx
    bool all_triangles = true;             // then face_start[f] = 3 f
    std::vector<uint32_t> triangle_faces;  // the face of each triangle, unless all faces are triangles
    size_t count() const { return all_triangles ? face_start.size() : triangle_faces.size(); }
    size_t face_of(size_t t) const { return all_triangles ? t : size_t(triangle_faces[t]); }
    // Corner c % 3 of triangle c / 3.
    const tinyobj::index_t& corner(size_t c) const {
      return all_triangles ? idx[c] : idx[face_start[triangle_faces[c / 3]] + c % 3];
    }
  };

  // What a shape's corners hold, and so which vertex attributes its mesh gets.
  struct CornerKinds {
    bool any_uv = false, any_normal = false, all_normals = true;
  };

  ShapeTriangles shape_triangles(const tinyobj::shape_t& s) const {
    const std::vector<unsigned char>& sizes = s.mesh.num_face_vertices;
    const size_t faces = sizes.size();
    ShapeTriangles tri{
        s.mesh.indices, {}, std::all_of(sizes.begin(), sizes.end(), [](unsigned char n) { return n == 3; }), {}};
    resize_on_present_pages(tri.face_start, faces);
    size_t corners = 3 * faces;
    if (tri.all_triangles) {
      tbb::parallel_for(tbb::blocked_range<size_t>(0, faces, 1 << 16), [&](const tbb::blocked_range<size_t>& r) {
        for (size_t f = r.begin(); f < r.end(); ++f) tri.face_start[f] = 3 * f;
      });
    } else {
      corners = 0;
      for (size_t f = 0; f < faces; ++f) {
        tri.face_start[f] = corners;
        corners += sizes[f];
        if (sizes[f] == 3) tri.triangle_faces.push_back(uint32_t(f));
      }
    }
    if (corners != tri.idx.size())
      throw Error(path_ + ": '" + s.name + "': inconsistent face data from the OBJ parser");
    return tri;
  }

  // A corner's normal index, or -1 (none, or one the file's normals cannot give).
  int corner_normal(const tinyobj::index_t& ix, bool normals_ok) const {
    return normals_ok && ix.normal_index >= 0 && normal_usable_[size_t(ix.normal_index)] ? ix.normal_index : -1;
  }
  static int corner_uv(const tinyobj::index_t& ix, bool uvs_ok) { return uvs_ok ? ix.texcoord_index : -1; }

  CornerKinds corner_kinds(const ShapeTriangles& tri, bool uvs_ok, bool normals_ok) const {
    return tbb::parallel_reduce(
        tbb::blocked_range<size_t>(0, 3 * tri.count(), 1 << 14), CornerKinds{},
        [&](const tbb::blocked_range<size_t>& r, CornerKinds acc) {
          for (size_t c = r.begin(); c < r.end(); ++c) {
            const tinyobj::index_t& ix = tri.corner(c);
            acc.any_uv |= corner_uv(ix, uvs_ok) >= 0;
            const bool has_normal = corner_normal(ix, normals_ok) >= 0;
            acc.any_normal |= has_normal;
            acc.all_normals &= has_normal;
          }
          return acc;
        },
        [](CornerKinds a, const CornerKinds& b) {
          return CornerKinds{a.any_uv || b.any_uv, a.any_normal || b.any_normal, a.all_normals && b.all_normals};
        });
  }

  // The material of each triangle: its library material, or the default one
  // (made, once, before the parallel loop reads it).
  std::vector<int> triangle_materials(const tinyobj::shape_t& s, const ShapeTriangles& tri) {
    const size_t triangles = tri.count(), library_materials = materials_.library().materials.size();
    auto library_material = [&](size_t t) {  // the triangle's material in the library, or -1
      const size_t f = tri.face_of(t);
      const int mid = f < s.mesh.material_ids.size() ? s.mesh.material_ids[f] : -1;
      return mid >= 0 && size_t(mid) < library_materials ? mid : -1;
    };
    const bool any_default = tbb::parallel_reduce(
        tbb::blocked_range<size_t>(0, triangles, 1 << 16), false,
        [&](const tbb::blocked_range<size_t>& r, bool acc) {
          for (size_t t = r.begin(); t < r.end() && !acc; ++t) acc = library_material(t) < 0;
          return acc;
        },
        std::logical_or<bool>());
    const int default_material = any_default ? materials_.default_material() : invalid;
    std::vector<int> face_mats;
    resize_on_present_pages(face_mats, triangles);
    tbb::parallel_for(tbb::blocked_range<size_t>(0, triangles, 1 << 16), [&](const tbb::blocked_range<size_t>& r) {
      for (size_t t = r.begin(); t < r.end(); ++t) {
        const int m = library_material(t);
        face_mats[t] = m >= 0 ? m : default_material;
      }
    });
    return face_mats;
  }

  int build_mesh(const tinyobj::shape_t& s, const tinyobj::attrib_t& a, bool uvs_ok, bool normals_ok) {
    const ShapeTriangles tri = shape_triangles(s);
    const std::vector<tinyobj::index_t>& idx = tri.idx;
    auto pos = [&](int v) { return vec3(a.vertices[3 * v], a.vertices[3 * v + 1], a.vertices[3 * v + 2]); };
    const CornerKinds kinds = corner_kinds(tri, uvs_ok, normals_ok);
    const bool any_uv = kinds.any_uv;
    // Normals wanted per vertex unless the file gives none and the caller
    // asked for facets: then the mesh has none and the renderer uses face normals.
    const bool generate = !kinds.all_normals;
    const bool per_vertex_normals = !(options_.flat && !kinds.any_normal);

    // Smooth generated normals (obj_smooth_normals.h): per position, shared
    // among the parts of a large mesh's read.
    const size_t position_count = a.vertices.size() / 3;
    std::vector<vec3> smooth;  // per position; zero where no face contributes
    if (generate && !options_.flat) {
      const size_t faces = s.mesh.num_face_vertices.size();
      const WorkShare* share = options_.share && faces >= options_.share_min_faces ? options_.share : nullptr;
      smooth = obj::smooth_normal_sums(a.vertices, {idx, tri.face_start, s.mesh.num_face_vertices}, share);
    }

    const size_t triangles = tri.count();
    if (triangles == 0) return invalid;
    Mesh mesh;
    mesh.name = s.name.empty() ? fs::path(path_).stem().string() : s.name;
    mesh.source_path = path_;
    // A corner's vertex is found by its key (position, uv, normal); a corner
    // without a normal: smooth ones are shared per position (key -1),
    // faceted ones belong to their face alone (key -2 - face).
    auto key_of = [&](size_t c) {
      const tinyobj::index_t& ix = tri.corner(c);
      const int n = corner_normal(ix, normals_ok);
      const int nkey = n >= 0 ? n : (!per_vertex_normals ? -1 : (options_.flat ? -2 - int(tri.face_of(c / 3)) : -1));
      return obj::CornerKey{ix.vertex_index, corner_uv(ix, uvs_ok), nkey};
    };
    // Without uvs, written normals and facets a corner's key is its position
    // alone (what key_of gives then, without its lookups).
    auto position_key_of = [&](size_t c) { return obj::CornerKey{tri.corner(c).vertex_index, -1, -1}; };
    obj::WeldedVertices welded = !any_uv && !kinds.any_normal && !options_.flat
                                     ? obj::weld_vertices(position_count, 3 * triangles, position_key_of)
                                     : obj::weld_vertices(position_count, 3 * triangles, key_of);
    const size_t vertices = welded.first_corner.size();
    resize_on_present_pages(mesh.positions, vertices);
    if (any_uv) resize_on_present_pages(mesh.uvs, vertices);
    if (per_vertex_normals) resize_on_present_pages(mesh.normals, vertices);
    if (has_colors_) resize_on_present_pages(mesh.colors, vertices);
    auto face_normal = [&](size_t f) {
      const size_t b = tri.face_start[f];
      vec3 p0 = pos(idx[b].vertex_index), p1 = pos(idx[b + 1].vertex_index), p2 = pos(idx[b + 2].vertex_index);
      vec3 n = glm::cross(p1 - p0, p2 - p0);
      float len = glm::length(n);
      return len > 0.f && std::isfinite(len) ? n / len : vec3(0.f);
    };
    // Each vertex from the first corner with its key.
    tbb::parallel_for(tbb::blocked_range<size_t>(0, vertices, 4096), [&](const tbb::blocked_range<size_t>& r) {
      for (size_t v = r.begin(); v < r.end(); ++v) {
        const size_t c = welded.first_corner[v];
        const tinyobj::index_t& ix = tri.corner(c);
        const int t = corner_uv(ix, uvs_ok), n = corner_normal(ix, normals_ok);
        const size_t p = size_t(ix.vertex_index);
        mesh.positions[v] = pos(ix.vertex_index);
        if (any_uv) mesh.uvs[v] = t >= 0 ? vec2(a.texcoords[2 * t], a.texcoords[2 * t + 1]) : vec2(0.f);
        if (per_vertex_normals) {
          vec3 nv(0.f);
          if (n >= 0) nv = vec3(a.normals[3 * n], a.normals[3 * n + 1], a.normals[3 * n + 2]);
          else if (options_.flat) nv = generate ? face_normal(tri.face_of(c / 3)) : vec3(0.f);
          else if (!smooth.empty()) nv = smooth[p];
          float len = glm::length(nv);
          mesh.normals[v] = len > 0.f && std::isfinite(len) ? nv / len : vec3(0.f);
        }
        if (has_colors_) mesh.colors[v] = vec3(a.colors[3 * p], a.colors[3 * p + 1], a.colors[3 * p + 2]);
      }
    });
    mesh.indices = std::move(welded.corner_vertex);
    std::vector<int> face_mats = triangle_materials(s, tri);
    bool uniform = std::all_of(face_mats.begin(), face_mats.end(), [&](int m) { return m == face_mats[0]; });
    mesh_node_material_ = face_mats[0];
    if (!uniform) mesh.face_materials = std::move(face_mats);
    scene_.meshes.push_back(std::move(mesh));
    return int(scene_.meshes.size()) - 1;
  }

  // ---- errors and warnings -------------------------------------------------

  [[noreturn]] void fail_from_tinyobj(const std::string& err) {
    std::string e = trim(err);
    // tinyobjloader: "Failed parse `f' line(e.g. zero value for face index. line 12.)"
    size_t at = e.rfind("line ");
    if (at != std::string::npos) {
      size_t line = std::strtoul(e.c_str() + at + 5, nullptr, 10);
      if (line > 0) {
        std::string what = e.find("`f'") != std::string::npos
                               ? "a face with an index of 0 or no number (OBJ indices start at 1)"
                           : e.find("`l'") != std::string::npos ? "a line with an index of 0 or no number"
                           : e.find("`p'") != std::string::npos ? "a point with an index of 0 or no number"
                                                                : e;
        throw Error(path_ + ":" + std::to_string(line) + ": " + what);
      }
    }
    throw Error(path_ + ": cannot read OBJ: " + (e.empty() ? std::string("unknown error") : e));
  }

  [[noreturn]] void fail_bad_index(int kind, size_t count) {
    BadIndex b;
    if (find_bad_index(std::string(text_), kind, &b))
      throw Error(path_ + ":" + std::to_string(b.line) + ": face refers to vertex " + std::to_string(b.index) +
                  " but only " + std::to_string(b.count) + " vertices are declared before it");
    throw Error(path_ + ": a face refers to a vertex that does not exist (the file has " + std::to_string(count) +
                " vertices)");
  }

  void warn_bad_index(int kind, size_t count, const char* what) {
    BadIndex b;
    std::string item = kind == 1 ? "texture coordinate " : "normal ";
    if (find_bad_index(std::string(text_), kind, &b))
      warn(path_ + ":" + std::to_string(b.line) + ": face refers to " + item + std::to_string(b.index) + " but only " +
           std::to_string(b.count) + " are declared before it; " + what + " of this file are ignored");
    else
      warn(path_ + ": faces refer to " + what + " that do not exist (the file has " + std::to_string(count) + "); " +
           what + " of this file are ignored");
  }

  void handle_tinyobj_warnings(const std::string& warn_text) {
    std::istringstream in(warn_text);
    std::string l;
    while (std::getline(in, l)) {
      l = trim(l);
      if (l.empty() || l == ".") continue;
      // Out-of-range indices are checked (with line numbers) by us; tinyobj
      // drops quads with a bad vertex index, so those are errors here.
      if (l.rfind("Vertex indices out of bounds", 0) == 0 || l.rfind("Face with invalid vertex index", 0) == 0)
        fail_bad_index(0, 0);
      if (l.rfind("Vertex normal indices out of bounds", 0) == 0 ||
          l.rfind("Vertex texcoord indices out of bounds", 0) == 0)
        continue;
      if (l.rfind("Degenerated face found", 0) == 0) l = "faces with fewer than three vertices are skipped";
      if (l.rfind("material [", 0) == 0) l += " (those faces use the default material)";
      warn(path_ + ": " + l);
    }
  }

  std::string path_;
  ObjReadOptions options_;
  std::vector<std::string>* warnings_;
  std::set<std::string> seen_warnings_;
  fs::path dir_;
  FileBytes file_;
  std::string_view text_;  // file_'s bytes
  Scene scene_;
  // The file's materials, into scene_ (declared after it: it holds a reference).
  obj::ObjMaterials materials_{path_, dir_, options_.access, scene_, [this](std::string w) { warn(std::move(w)); }};
  int mesh_node_material_ = invalid;
  bool has_colors_ = false;
  std::vector<uint8_t> normal_usable_;  // per written normal
};

}  // namespace

Scene read_obj_scene(const std::string& path, const ObjReadOptions& options, std::vector<std::string>* warnings) {
  return ObjReader(path, options, warnings).read();
}

}  // namespace rayform
