#include "rayform/importers/obj/obj_reader.h"

#include "rayform/importers/file_bytes.h"
#include "rayform/importers/obj/mtl_library.h"
#include "rayform/importers/obj/obj_bad_index.h"
#include "rayform/importers/obj/obj_parallel_parse.h"
#include "rayform/importers/obj/obj_pbr_material.h"
#include "rayform/importers/obj/obj_side_files.h"
#include "rayform/importers/obj/obj_smooth_normals.h"
#include "rayform/importers/obj/obj_vertex_weld.h"
#include "rayform/importers/obj/text_stream_buffer.h"

#include "rayform/base/error.h"

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
#include <map>
#include <set>
#include <sstream>
#include <string_view>

namespace rayform {
namespace fs = std::filesystem;
namespace {

using obj::BadIndex;
using obj::find_bad_index;
using obj::is_pbr_material;
using obj::mtl_keywords;
using obj::MtlLibrary;
using obj::pbr_material;
using obj::PreloadedMaterials;
using obj::resolve_beside;
using obj::Resolved;
using obj::split_mtllib;

// Grey of the material given to faces without a (known) material: light
// enough to read, dark enough that a head-on light does not clip it.
constexpr float default_grey = 0.8f;

// Smaller files are parsed in one piece: threads do not pay there.
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

std::string trim(std::string s) {
  size_t b = s.find_first_not_of(" \t\r\n");
  if (b == std::string::npos) return {};
  size_t e = s.find_last_not_of(" \t\r\n");
  return s.substr(b, e - b + 1);
}

class ObjReader {
 public:
  ObjReader(const std::string& path, const ObjReadOptions& options, std::vector<std::string>* warnings)
      : path_(path), options_(options), warnings_(warnings), dir_(fs::path(path).parent_path()) {}

  Scene read() {
    file_ = FileBytes(path_, "OBJ file");
    text_ = file_.view();
    load_material_libraries();

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

    convert_materials();

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
    MaterialReaderFactory readers = [&] { return std::make_unique<PreloadedMaterials>(lib_); };
    const WorkShare* share = options_.share && options_.share->shared() ? options_.share : nullptr;
    size_t chunk = options_.parse_chunk_bytes;
    if (chunk == 0 && share) {
      // The same chunks on every part, whatever threads each has.
      chunk =
          text_.size() >= min_parallel_bytes ? text_.size() / (size_t(share->parts) * shared_chunks_per_part) + 1 : 0;
    } else if (chunk == 0) {
      const size_t threads = tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism);
      chunk = threads > 1 && text_.size() >= min_parallel_bytes ? text_.size() / (chunks_per_thread * threads) + 1 : 0;
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

  // ---- materials ---------------------------------------------------------

  // The `mtllib` lines, found by searching the text for the word (not line by
  // line: a mesh file is mostly vertices and faces).
  void load_material_libraries() {
    const std::string_view text(text_);
    size_t line_no = 1, counted_to = 0;  // line_no: the line at offset counted_to
    std::set<std::string> loaded;
    for (size_t at = text.find("mtllib"); at != std::string_view::npos; at = text.find("mtllib", at + 6)) {
      const size_t newline_before = text.rfind('\n', at);
      const size_t line_start = newline_before == std::string_view::npos ? 0 : newline_before + 1;
      const size_t b = at - line_start;  // where the word starts in its line
      if (text.substr(line_start, b).find_first_not_of(" \t") != std::string_view::npos) continue;
      const size_t line_end = std::min(text.find('\n', at), text.size());
      const std::string line(text.substr(line_start, line_end - line_start));
      line_no += size_t(std::count(text.begin() + counted_to, text.begin() + line_start, '\n'));
      counted_to = line_start;
      if (b + 6 < line.size() && line[b + 6] != ' ' && line[b + 6] != '\t') continue;
      std::string rest = trim(line.substr(b + 6));
      std::string where = path_ + ":" + std::to_string(line_no);
      if (rest.empty()) {
        warn(where + ": mtllib names no file");
        continue;
      }
      for (const std::string& name : split_mtllib(rest, dir_)) {
        Resolved r = resolve_beside(dir_, name);
        if (!r.found) {
          warn(where + ": cannot find material library '" + name +
               "'; its materials are replaced by the default material");
          continue;
        }
        if (std::string problem = referenced_file_problem(path_, "mtllib", name, r.path, options_.access);
            !problem.empty())
          throw Error(where + ": " + problem);
        if (r.by_name_only)
          warn(where + ": material library '" + name + "' not found as written; using " + r.path.string());
        std::error_code ec;
        std::string key = fs::weakly_canonical(r.path, ec).string();
        if (!loaded.insert(key).second) continue;
        load_mtl(r.path);
      }
    }
  }

  void load_mtl(const fs::path& file) {
    std::ifstream f(file, std::ios::binary);
    std::ostringstream ss;
    ss << f.rdbuf();
    if (!f) {
      warn(file.string() + ": cannot read material library");
      return;
    }
    std::string text = ss.str();
    std::map<std::string, std::set<std::string>> keywords = mtl_keywords(text);
    std::istringstream in(text);
    std::string w, e;
    size_t first = lib_.materials.size();
    tinyobj::LoadMtl(&lib_.names, &lib_.materials, &in, &w, &e);
    for (size_t i = first; i < lib_.materials.size(); ++i) {
      lib_.dirs.push_back(file.parent_path());
      lib_.keywords.push_back(keywords[lib_.materials[i].name]);
    }
    std::istringstream wl(w + e);
    std::string l;
    while (std::getline(wl, l))
      if (!trim(l).empty()) warn(file.string() + ": " + trim(l));
  }

  // The path of a material's texture file, resolved beside its .mtl; "" when
  // it cannot be found (warned about).
  std::string texture_path(const std::string& name, const fs::path& mtl_dir, const std::string& material,
                           const char* slot) {
    Resolved r = resolve_beside(mtl_dir, name);
    if (!r.found) {
      warn(path_ + ": material '" + material + "': cannot find " + slot + " texture '" + name + "' (looked in " +
           mtl_dir.string() + "); the material has no " + slot + " texture");
      return {};
    }
    if (std::string problem = referenced_file_problem(path_, slot, name, r.path, options_.access); !problem.empty())
      throw Error(path_ + ": material '" + material + "': " + problem);
    if (r.by_name_only)
      warn(path_ + ": material '" + material + "': " + slot + " texture '" + name + "' not found as written; using " +
           r.path.string());
    return r.path.lexically_normal().string();
  }

  // A texture of a material: resolved beside its .mtl; missing = warning.
  int texture(const std::string& name, const fs::path& mtl_dir, const std::string& material, const char* slot,
              bool srgb, bool clamp) {
    if (name.empty()) return invalid;
    const std::string path = texture_path(name, mtl_dir, material, slot);
    if (path.empty()) return invalid;
    std::string key = path + (srgb ? "|srgb" : "|raw") + (clamp ? "|clamp" : "|repeat");
    auto it = texture_cache_.find(key);
    if (it != texture_cache_.end()) return it->second;
    Texture t;
    t.name = name;
    t.path = path;
    t.srgb = srgb;
    t.lookup = Texture::Lookup::standard;
    t.wrap_u = t.wrap_v = clamp ? Texture::Wrap::clamp : Texture::Wrap::repeat;
    t.filter = Texture::Filter::linear;
    scene_.textures.push_back(std::move(t));
    int index = int(scene_.textures.size()) - 1;
    texture_cache_[key] = index;
    return index;
  }

  // How the PBR materials of the .mtl in `dir` find their textures.
  obj::MtlTextures& pbr_textures(const fs::path& dir) {
    pbr_textures_.resolve = [this, dir](const std::string& name, const char* slot) {
      return texture_path(name, dir, current_material_, slot);
    };
    pbr_textures_.file_texture = [this, dir](const std::string& name, const char* slot, bool srgb, bool clamp) {
      return texture(name, dir, current_material_, slot, srgb, clamp);
    };
    pbr_textures_.add = [this](Texture t) {
      scene_.textures.push_back(std::move(t));
      return int(scene_.textures.size()) - 1;
    };
    pbr_textures_.warn = [this](const std::string& w) { warn(path_ + ": " + w); };
    return pbr_textures_;
  }

  void convert_materials() {
    for (size_t i = 0; i < lib_.materials.size(); ++i) {
      const tinyobj::material_t& tm = lib_.materials[i];
      const fs::path& dir = lib_.dirs[i];
      current_material_ = tm.name;
      Material m;
      m.name = tm.name;
      m.texture_modulates = true;
      m.double_sided = true;
      m.two_sided_lighting = true;  // OBJ has no culling: both sides are lit alike
      bool srgb = tm.diffuse_texopt.colorspace != "linear";
      m.diffuse_texture = texture(tm.diffuse_texname, dir, tm.name, "map_Kd", srgb, tm.diffuse_texopt.clamp);
      // Kd absent: with a map_Kd the texel is the colour (Kd = 1, as
      // exporters that leave Kd out mean); without one, the default grey.
      // (tinyobjloader would give 0.6 or black.)
      if (lib_.has(i, "Kd")) m.diffuse = vec3(tm.diffuse[0], tm.diffuse[1], tm.diffuse[2]);
      else m.diffuse = vec3(m.diffuse_texture != invalid ? 1.f : default_grey);
      if (is_pbr_material(lib_.keywords[i])) {
        scene_.materials.push_back(pbr_material(tm, lib_.keywords[i], m.diffuse, m.diffuse_texture, pbr_textures(dir)));
        continue;
      }
      if (m.diffuse_texture != invalid) {
        // map_Kd -s/-o: uv' = uv * s + o, the shader's transform with no rotation.
        m.uv_transform.scale = vec2(tm.diffuse_texopt.scale[0], tm.diffuse_texopt.scale[1]);
        m.uv_transform.offset = vec2(tm.diffuse_texopt.origin_offset[0], tm.diffuse_texopt.origin_offset[1]);
      }
      m.specular = vec3(tm.specular[0], tm.specular[1], tm.specular[2]);
      m.shininess = tm.shininess;
      // Ns 0 would make (L.R)^0 = 1: a constant "highlight" over the whole lit
      // side. Exporters write Ns 0 for "no highlight" (Blender: roughness 1).
      if (!(m.shininess > 0.f)) {
        m.shininess = 0.f;
        m.specular = vec3(0.f);
      }
      m.emission = vec3(tm.emission[0], tm.emission[1], tm.emission[2]);
      m.bump_texture = texture(tm.bump_texname, dir, tm.name, "map_Bump", false, tm.bump_texopt.clamp);
      if (tm.dissolve < 1.f)
        warn(path_ + ": material '" + tm.name + "': transparency (d " + std::to_string(tm.dissolve) +
             ") is not rendered; the material is opaque");
      // Ka has no place in the course Phong model (ambient = scene ambient x K).
      std::vector<std::string> unused;
      if (!tm.ambient_texname.empty()) unused.push_back("map_Ka");
      if (!tm.specular_texname.empty()) unused.push_back("map_Ks");
      if (!tm.specular_highlight_texname.empty()) unused.push_back("map_Ns");
      if (!tm.emissive_texname.empty()) unused.push_back("map_Ke");
      if (!tm.alpha_texname.empty()) unused.push_back("map_d");
      if (!tm.displacement_texname.empty()) unused.push_back("disp");
      if (!tm.reflection_texname.empty()) unused.push_back("refl");
      if (!unused.empty()) {
        std::string list;
        for (const std::string& u : unused) list += (list.empty() ? "" : ", ") + u;
        warn(path_ + ": material '" + tm.name + "': " + list + " not used by the Phong shader; ignored");
      }
      scene_.materials.push_back(std::move(m));
    }
  }

  int default_material() {
    if (default_material_ == invalid) {
      Material m;
      m.name = "default";
      m.diffuse = vec3(default_grey);
      m.texture_modulates = true;
      m.two_sided_lighting = true;
      scene_.materials.push_back(m);
      default_material_ = int(scene_.materials.size()) - 1;
    }
    return default_material_;
  }

  // ---- geometry ----------------------------------------------------------

  int build_mesh(const tinyobj::shape_t& s, const tinyobj::attrib_t& a, bool uvs_ok, bool normals_ok) {
    const std::vector<tinyobj::index_t>& idx = s.mesh.indices;
    const size_t faces = s.mesh.num_face_vertices.size();
    // After triangulation every face is a triangle; be defensive anyway.
    std::vector<size_t> face_start(faces);
    {
      size_t o = 0;
      for (size_t f = 0; f < faces; ++f) {
        face_start[f] = o;
        o += s.mesh.num_face_vertices[f];
      }
      if (o != idx.size()) throw Error(path_ + ": '" + s.name + "': inconsistent face data from the OBJ parser");
    }
    auto pos = [&](int v) { return vec3(a.vertices[3 * v], a.vertices[3 * v + 1], a.vertices[3 * v + 2]); };
    auto corner_normal = [&](const tinyobj::index_t& ix) {
      return normals_ok && ix.normal_index >= 0 && normal_usable_[size_t(ix.normal_index)] ? ix.normal_index : -1;
    };
    auto corner_uv = [&](const tinyobj::index_t& ix) { return uvs_ok ? ix.texcoord_index : -1; };

    bool any_uv = false, any_normal = false, all_normals = true;
    for (size_t f = 0; f < faces; ++f) {
      if (s.mesh.num_face_vertices[f] != 3) continue;
      for (int k = 0; k < 3; ++k) {
        const tinyobj::index_t& ix = idx[face_start[f] + k];
        any_uv |= corner_uv(ix) >= 0;
        bool hn = corner_normal(ix) >= 0;
        any_normal |= hn;
        all_normals &= hn;
      }
    }
    // Normals wanted per vertex unless the file gives none and the caller
    // asked for facets: then the mesh has none and the renderer uses face normals.
    const bool generate = !all_normals;
    const bool per_vertex_normals = !(options_.flat && !any_normal);

    // Smooth generated normals (obj_smooth_normals.h): per position, shared
    // among the parts of a large mesh's read.
    const size_t position_count = a.vertices.size() / 3;
    std::vector<vec3> smooth;  // per position; zero where no face contributes
    if (generate && !options_.flat) {
      const WorkShare* share = options_.share && faces >= options_.share_min_faces ? options_.share : nullptr;
      smooth = obj::smooth_normal_sums(a.vertices, {idx, face_start, s.mesh.num_face_vertices}, share);
    }

    Mesh mesh;
    mesh.name = s.name.empty() ? fs::path(path_).stem().string() : s.name;
    mesh.source_path = path_;
    // The triangles: after tinyobjloader's triangulation every face is one
    // (faces of another size are skipped, defensively).
    const bool all_triangles = std::all_of(s.mesh.num_face_vertices.begin(), s.mesh.num_face_vertices.end(),
                                           [](unsigned char n) { return n == 3; });
    std::vector<uint32_t> triangle_faces;  // the face of each triangle, unless all faces are triangles
    if (!all_triangles)
      for (size_t f = 0; f < faces; ++f)
        if (s.mesh.num_face_vertices[f] == 3) triangle_faces.push_back(uint32_t(f));
    const size_t triangles = all_triangles ? faces : triangle_faces.size();
    if (triangles == 0) return invalid;
    auto face_of = [&](size_t t) { return all_triangles ? t : size_t(triangle_faces[t]); };
    // Corner c is idx[c] when all faces are triangles (face_start[f] = 3 f).
    auto corner = [&](size_t c) -> const tinyobj::index_t& {
      return all_triangles ? idx[c] : idx[face_start[triangle_faces[c / 3]] + c % 3];
    };
    // A corner's vertex is found by its key (position, uv, normal); a corner
    // without a normal: smooth ones are shared per position (key -1),
    // faceted ones belong to their face alone (key -2 - face).
    auto key_of = [&](size_t c) {
      const tinyobj::index_t& ix = corner(c);
      const int n = corner_normal(ix);
      const int nkey = n >= 0 ? n : (!per_vertex_normals ? -1 : (options_.flat ? -2 - int(face_of(c / 3)) : -1));
      return obj::CornerKey{ix.vertex_index, corner_uv(ix), nkey};
    };
    obj::WeldedVertices welded = obj::weld_vertices(position_count, 3 * triangles, key_of);
    const size_t vertices = welded.first_corner.size();
    mesh.positions.resize(vertices);
    if (any_uv) mesh.uvs.resize(vertices);
    if (per_vertex_normals) mesh.normals.resize(vertices);
    if (has_colors_) mesh.colors.resize(vertices);
    auto face_normal = [&](size_t f) {
      const size_t b = face_start[f];
      vec3 p0 = pos(idx[b].vertex_index), p1 = pos(idx[b + 1].vertex_index), p2 = pos(idx[b + 2].vertex_index);
      vec3 n = glm::cross(p1 - p0, p2 - p0);
      float len = glm::length(n);
      return len > 0.f && std::isfinite(len) ? n / len : vec3(0.f);
    };
    // Each vertex from the first corner with its key.
    tbb::parallel_for(tbb::blocked_range<size_t>(0, vertices, 4096), [&](const tbb::blocked_range<size_t>& r) {
      for (size_t v = r.begin(); v < r.end(); ++v) {
        const size_t c = welded.first_corner[v];
        const tinyobj::index_t& ix = corner(c);
        const int t = corner_uv(ix), n = corner_normal(ix);
        const size_t p = size_t(ix.vertex_index);
        mesh.positions[v] = pos(ix.vertex_index);
        if (any_uv) mesh.uvs[v] = t >= 0 ? vec2(a.texcoords[2 * t], a.texcoords[2 * t + 1]) : vec2(0.f);
        if (per_vertex_normals) {
          vec3 nv(0.f);
          if (n >= 0) nv = vec3(a.normals[3 * n], a.normals[3 * n + 1], a.normals[3 * n + 2]);
          else if (options_.flat) nv = generate ? face_normal(face_of(c / 3)) : vec3(0.f);
          else if (!smooth.empty()) nv = smooth[p];
          float len = glm::length(nv);
          mesh.normals[v] = len > 0.f && std::isfinite(len) ? nv / len : vec3(0.f);
        }
        if (has_colors_) mesh.colors[v] = vec3(a.colors[3 * p], a.colors[3 * p + 1], a.colors[3 * p + 2]);
      }
    });
    mesh.indices = std::move(welded.corner_vertex);
    std::vector<int> face_mats(triangles);
    for (size_t t = 0; t < triangles; ++t) {
      const size_t f = face_of(t);
      int mid = f < s.mesh.material_ids.size() ? s.mesh.material_ids[f] : -1;
      face_mats[t] = mid >= 0 && size_t(mid) < lib_.materials.size() ? mid : default_material();
    }
    if (mesh.indices.empty()) return invalid;
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
  MtlLibrary lib_;
  Scene scene_;
  std::map<std::string, int> texture_cache_;
  obj::MtlTextures pbr_textures_;  // the PBR materials' textures, packed ones included
  std::string current_material_;   // the material being converted, for messages
  int default_material_ = invalid;
  int mesh_node_material_ = invalid;
  bool has_colors_ = false;
  std::vector<uint8_t> normal_usable_;  // per written normal
};

}  // namespace

Scene read_obj_scene(const std::string& path, const ObjReadOptions& options, std::vector<std::string>* warnings) {
  return ObjReader(path, options, warnings).read();
}

}  // namespace rayform
