#include "rayform/importers/obj/obj_parallel_parse.h"

#include "rayform/importers/obj/obj_chunk_scan.h"
#include "rayform/importers/obj/obj_parse_bytes.h"
#include "rayform/importers/obj/obj_plain_chunk.h"
#include "rayform/importers/obj/obj_polygon_split.h"
#include "rayform/importers/obj/text_stream_buffer.h"
#include "rayform/base/error.h"
#include "rayform/base/populate_pages.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cstdint>
#include <exception>
#include <cstring>
#include <istream>
#include <span>
#include <sstream>

namespace rayform {
namespace {

using obj::ChunkScan;
using obj::for_each_line;
using obj::is_vertex_line;
using obj::Line;

// The chunks: about `chunk_bytes` each, cut after a '\n'.
std::vector<size_t> chunk_starts(std::string_view text, size_t chunk_bytes) {
  std::vector<size_t> starts{0};
  for (size_t at = chunk_bytes; at < text.size(); at += chunk_bytes) {
    size_t nl = text.find('\n', std::max(at, starts.back()));
    if (nl == std::string_view::npos || nl + 1 >= text.size()) break;
    starts.push_back(nl + 1);
    at = nl + 1;
  }
  starts.push_back(text.size());
  return starts;
}

// The state lines in force at the start of each chunk, in file order.
std::vector<std::string> chunk_prefixes(const std::vector<ChunkScan>& scans) {
  std::vector<std::string> prefixes(scans.size());
  Line mtllib, usemtl, group, smoothing;
  for (size_t k = 0; k < scans.size(); ++k) {
    std::vector<Line> lines;
    for (const Line& l : {mtllib, usemtl, group, smoothing})
      if (!l.empty()) lines.push_back(l);
    std::sort(lines.begin(), lines.end(), [](const Line& a, const Line& b) { return a.at < b.at; });
    for (const Line& l : lines) prefixes[k].append(l.text).append("\n");
    const ChunkScan& s = scans[k];
    if (mtllib.empty()) mtllib = s.first_mtllib;
    if (!s.last_usemtl.empty()) usemtl = s.last_usemtl;
    if (!s.last_group.empty()) group = s.last_group;
    if (!s.last_smoothing.empty()) smoothing = s.last_smoothing;
  }
  return prefixes;
}

// The warnings of a chunk that the whole-file parse gives alike: unknown
// materials (no line number). Index bounds are checked over the whole text
// by the caller; anything else: false.
bool keep_warnings(const std::string& warn, std::string* kept) {
  std::istringstream in(warn);
  std::string l;
  while (std::getline(in, l)) {
    if (l.empty()) continue;
    if (l.rfind("material [", 0) == 0) kept->append(l).append("\n");
    else if (l.rfind("Vertex indices out of bounds", 0) != 0 &&
             l.rfind("Vertex normal indices out of bounds", 0) != 0 &&
             l.rfind("Vertex texcoord indices out of bounds", 0) != 0)
      return false;
  }
  return true;
}

using ChunkResult = obj::ChunkParse;

// What LoadObj gives the faces behind a chunk's state lines (`prefix`): a
// face put behind them, parsed so, tells. False where that parse fails or
// warns of more than keep_warnings keeps (`warn` gets what it keeps).
bool face_state(const std::string& prefix, const MaterialReaderFactory& readers, obj::FaceState* state,
                std::string* warn) {
  TextStreamBuffer buffer(prefix, "f 1 2 3\n");
  std::istream in(&buffer);
  std::unique_ptr<tinyobj::MaterialReader> reader = readers();
  tinyobj::attrib_t attrib;
  std::vector<tinyobj::shape_t> shapes;
  std::vector<tinyobj::material_t> materials;
  std::string w, err;
  if (!tinyobj::LoadObj(&attrib, &shapes, &materials, &w, &err, &in, reader.get(), /*triangulate*/ false,
                        /*default_vcols_fallback*/ false) ||
      !keep_warnings(w, warn) || shapes.size() != 1 || shapes[0].mesh.material_ids.size() != 1 ||
      shapes[0].mesh.smoothing_group_ids.size() != 1)
    return false;
  state->shape_name = shapes[0].name;
  state->material = shapes[0].mesh.material_ids[0];
  state->smoothing_group = shapes[0].mesh.smoothing_group_ids[0];
  return true;
}

// The chunk's shapes are those of its sections with faces, each face of
// three corners or more, and its vertices those of its `v` lines.
bool shapes_match_scan(const ChunkResult& r, const ChunkScan& s) {
  if (r.attrib.vertices.size() != 3 * s.vertex_lines) return false;
  size_t next = 0, polygons = 0;
  for (size_t faces : s.section_faces) {
    if (faces == 0) continue;
    if (next == r.shapes.size()) return false;
    const tinyobj::mesh_t& m = r.shapes[next++].mesh;
    if (m.num_face_vertices.size() != faces || m.material_ids.size() != faces) return false;
    size_t corners = 0;
    for (const unsigned char n : m.num_face_vertices) {
      if (n < 3) return false;
      corners += n;
      polygons += n > 3;
    }
    if (m.indices.size() != corners) return false;
  }
  for (const tinyobj::shape_t& shape : r.shapes)
    if (!shape.lines.indices.empty() || !shape.points.indices.empty() || !shape.mesh.tags.empty()) return false;
  return next == r.shapes.size() && polygons == s.polygon_vertices_before.size();
}

// Whether every corner of the chunk's polygons names a vertex declared before
// the polygon's line. LoadObj splits a polygon when its group ends, by the
// vertices read by then, and drops one naming a later vertex; a polygon that
// names only earlier ones is split alike whole or in chunks.
bool polygons_name_earlier_vertices(const ChunkResult& r, const ChunkScan& s, size_t first_vertex) {
  size_t polygon = 0;
  for (const tinyobj::shape_t& shape : r.shapes) {
    size_t at = 0;
    for (const unsigned char n : shape.mesh.num_face_vertices) {
      if (n > 3) {
        const size_t declared = first_vertex + s.polygon_vertices_before[polygon++];
        for (size_t k = 0; k < n; ++k)
          if (size_t(shape.mesh.indices[at + k].vertex_index) >= declared) return false;
      }
      at += n;
    }
  }
  return true;
}

// The text of the `v` lines that declared `wanted` (sorted vertex numbers,
// 0-based), found by counting the `v` lines of the chunks that hold them.
std::vector<std::string_view> vertex_line_texts(std::string_view text, const std::vector<size_t>& starts,
                                                const std::vector<size_t>& first_vertex,
                                                const std::vector<int>& wanted) {
  std::vector<std::string_view> lines(wanted.size());
  size_t next = 0;
  for (size_t k = 0; k + 1 < starts.size() && next < wanted.size(); ++k) {
    if (size_t(wanted[next]) >= first_vertex[k + 1]) continue;
    size_t vertex = first_vertex[k];
    for_each_line(text, starts[k], starts[k + 1], [&](const Line&, std::string_view t) {
      if (!is_vertex_line(t)) return true;
      if (size_t(wanted[next]) == vertex) lines[next++] = t;
      ++vertex;
      return next < wanted.size() && size_t(wanted[next]) < first_vertex[k + 1];
    });
  }
  return lines;
}

// The part of a shared parse that chunk k falls to: the chunks are dealt
// in turn, so that each part gets as many bytes (the chunks are of about
// one size) and as much of each kind of line (a file of vertices then
// faces would give the faces, which take longer to parse per byte, to the
// last parts if each took a run of the text).
int chunk_part(size_t k, int parts) { return int(k % size_t(parts)); }

// Each part scans the chunks that fall to it, and one exchange gives every
// part every chunk's scan; false on every part when a chunk is not
// supported. What a part throws travels as its message, and every part
// then throws it.
bool scan_shared(const WorkShare& share, std::string_view text, const std::vector<size_t>& starts,
                 std::vector<ChunkScan>* scans) {
  std::vector<ChunkScan>& s = *scans;
  const size_t n = s.size();
  std::vector<std::byte> bytes;
  try {
    std::vector<size_t> mine;
    for (size_t k = 0; k < n; ++k)
      if (chunk_part(k, share.parts) == share.part) mine.push_back(k);
    tbb::parallel_for(size_t(0), mine.size(),
                      [&](size_t i) { s[mine[i]] = obj::scan_chunk(text, starts[mine[i]], starts[mine[i] + 1]); });
    bytes = obj::scan_bytes(mine, s);
  } catch (...) {
    bytes = obj::failed_scan_bytes(current_exception_message());
  }
  std::vector<std::vector<std::byte>> all = share.exchange(std::move(bytes));
  if (all.size() != size_t(share.parts))
    throw Error("shared OBJ parse: " + std::to_string(all.size()) + " parts answered, not " +
                std::to_string(share.parts) + " (a bug)");
  for (size_t p = 0; p < all.size(); ++p) {
    std::string failure;
    if (!obj::scan_bytes_ok(all[p], &failure))
      throw Error("scanning OBJ text in chunks: part " + std::to_string(p) + " failed" +
                  (failure.empty() ? "" : ": " + failure));
  }
  std::vector<uint8_t> received(n, 0);
  for (size_t p = 0; p < all.size(); ++p) {
    for (size_t k : obj::read_scan_bytes(all[p], text, &s))
      if (chunk_part(k, share.parts) != int(p) || received[k]++)
        throw Error("shared OBJ parse: part " + std::to_string(p) + " sent the scan of chunk " + std::to_string(k) +
                    ", not its own (a bug)");
  }
  for (size_t k = 0; k < n; ++k)
    if (!received[k]) throw Error("shared OBJ parse: no part sent the scan of chunk " + std::to_string(k) + " (a bug)");
  return std::all_of(s.begin(), s.end(), [](const ChunkScan& c) { return c.supported; });
}

// Each part parses the chunks that fall to it, and one exchange gives every
// part every other chunk's result. Nothing is thrown between the first
// chunk and the exchange (a part that threw there would leave the others
// waiting): what a chunk throws travels as its error, and every part then
// throws it.
//
// `in_place`: the other chunks' face arrays are left in their bytes
// (obj::read_chunk_bytes), which move to `kept`.
void parse_shared(const WorkShare& share, const std::function<void(size_t)>& parse_chunk,
                  std::vector<ChunkResult>* results, bool in_place, std::vector<std::vector<std::byte>>* kept) {
  std::vector<ChunkResult>& r = *results;
  const size_t n = r.size();
  std::vector<size_t> mine;
  for (size_t k = 0; k < n; ++k)
    if (chunk_part(k, share.parts) == share.part) mine.push_back(k);
  std::vector<std::byte> bytes;
  try {
    tbb::parallel_for(size_t(0), mine.size(), [&](size_t i) {
      try {
        parse_chunk(mine[i]);
      } catch (...) {
        r[mine[i]] = ChunkResult{};
        r[mine[i]].error = current_exception_message();
      }
    });
    size_t size = 0;
    for (size_t k : mine) size += obj::chunk_bytes_size(r[k]);
    bytes.reserve(size);
    for (size_t k : mine) obj::append_chunk_bytes(k, r[k], &bytes);
  } catch (...) {
    ChunkResult failed;
    failed.error = current_exception_message();
    bytes.clear();
    for (size_t k : mine) {
      obj::append_chunk_bytes(k, failed, &bytes);
      r[k] = failed;
    }
  }
  const size_t sent = bytes.size();
  std::vector<std::vector<std::byte>> all = share.exchange(std::move(bytes));
  if (all.size() != size_t(share.parts))
    throw Error("shared OBJ parse: " + std::to_string(all.size()) + " parts answered, not " +
                std::to_string(share.parts) + " (a bug)");
  // This part's own chunks are its results already (not read back from its bytes).
  std::vector<uint8_t> received(n, 0);
  for (size_t k : mine) received[k] = 1;
  if (all[size_t(share.part)].size() != sent)
    throw Error("shared OBJ parse: part " + std::to_string(share.part) + "'s bytes came back changed (a bug)");
  for (size_t p = 0; p < all.size(); ++p) {
    if (p == size_t(share.part)) continue;
    for (size_t k : obj::read_chunk_bytes(all[p], &r, in_place))
      if (chunk_part(k, share.parts) != int(p) || received[k]++)
        throw Error("shared OBJ parse: part " + std::to_string(p) + " sent chunk " + std::to_string(k) +
                    ", not its own (a bug)");
    if (!in_place) std::vector<std::byte>().swap(all[p]);
  }
  if (in_place) *kept = std::move(all);
  for (size_t k = 0; k < n; ++k) {
    if (!received[k]) throw Error("shared OBJ parse: no part sent chunk " + std::to_string(k) + " (a bug)");
    if (!r[k].error.empty())
      throw Error("parsing OBJ text in chunks: part " + std::to_string(chunk_part(k, share.parts)) +
                  " failed: " + r[k].error);
  }
}

// The chunks' vertex arrays (and their warnings) concatenated into `o`, the
// colours kept only when every chunk has them; returns the first vertex of
// each chunk (0-based), then the count. Each array is sized once and the
// chunks' pieces copied in by parallel tasks (a single chunk's moved).
std::vector<size_t> join_vertex_arrays(std::vector<ChunkResult>& results, const std::vector<ChunkScan>& scans,
                                       ObjParse& o) {
  const size_t n = results.size();
  std::vector<size_t> first_vertex(n + 1, 0);  // the first vertex of each chunk (0-based), then the count
  bool all_colors = true;
  for (size_t k = 0; k < n; ++k) {
    all_colors &= results[k].attrib.colors.size() == results[k].attrib.vertices.size();
    o.warn += results[k].warn;
    first_vertex[k + 1] = first_vertex[k] + scans[k].vertex_lines;
  }
  using Array = std::vector<tinyobj::real_t>;
  std::vector<std::pair<Array tinyobj::attrib_t::*, Array*>> arrays = {
      {&tinyobj::attrib_t::vertices, &o.attrib.vertices},
      {&tinyobj::attrib_t::normals, &o.attrib.normals},
      {&tinyobj::attrib_t::texcoords, &o.attrib.texcoords}};
  if (all_colors) arrays.push_back({&tinyobj::attrib_t::colors, &o.attrib.colors});
  if (n == 1) {  // one chunk (one thread): its arrays are the joined ones
    for (const auto& [member, to] : arrays) *to = std::move(results[0].attrib.*member);
    return first_vertex;
  }
  std::vector<size_t> at(n + 1);  // where each chunk's piece of one array goes
  for (const auto& array : arrays) {
    // Named, not bound: clang's lambdas may not capture a structured binding.
    Array tinyobj::attrib_t::*const member = array.first;
    Array* const to = array.second;
    for (size_t k = 0; k < n; ++k) at[k + 1] = at[k] + (results[k].attrib.*member).size();
    resize_on_present_pages(*to, at[n]);
    tbb::parallel_for(size_t(0), n, [&](size_t k) {
      const Array& from = results[k].attrib.*member;
      std::copy(from.begin(), from.end(), to->begin() + ptrdiff_t(at[k]));
    });
  }
  return first_vertex;
}

// Whether every corner names one of the `vertex_count` joined vertices.
bool positions_in_range(std::span<const tinyobj::index_t> corners, size_t vertex_count) {
  return std::all_of(corners.begin(), corners.end(), [&](const tinyobj::index_t& ix) {
    return ix.vertex_index >= 0 && size_t(ix.vertex_index) < vertex_count;
  });
}

// A piece's face arrays copied into `to` from its corner `corner` and face `face` on.
void copy_faces(const tinyobj::mesh_t& from, tinyobj::mesh_t& to, size_t corner, size_t face) {
  std::copy(from.indices.begin(), from.indices.end(), to.indices.begin() + ptrdiff_t(corner));
  std::copy(from.num_face_vertices.begin(), from.num_face_vertices.end(),
            to.num_face_vertices.begin() + ptrdiff_t(face));
  std::copy(from.material_ids.begin(), from.material_ids.end(), to.material_ids.begin() + ptrdiff_t(face));
  std::copy(from.smoothing_group_ids.begin(), from.smoothing_group_ids.end(),
            to.smoothing_group_ids.begin() + ptrdiff_t(face));
}

// Whether every face index of every chunk names a vertex of the `vertex_count`
// joined ones.
bool face_indices_in_range(const std::vector<ChunkResult>& results, size_t vertex_count) {
  const size_t n = results.size();
  std::vector<uint8_t> indices_ok(n, 1);
  tbb::parallel_for(size_t(0), n, [&](size_t k) {
    for (const tinyobj::shape_t& s : results[k].shapes)
      if (!positions_in_range(s.mesh.indices, vertex_count)) indices_ok[k] = 0;
  });
  return std::find(indices_ok.begin(), indices_ok.end(), 0) == indices_ok.end();
}

// The chunks' polygons split into triangles as LoadObj splits them, which
// needs the text of the `v` lines of their corners (`positions`: the joined
// vertex arrays); false where a polygon names a vertex declared after it or
// cannot be split so.
bool split_polygons(std::string_view text, const std::vector<size_t>& starts, const std::vector<ChunkScan>& scans,
                    const std::vector<size_t>& first_vertex, const std::vector<tinyobj::real_t>& positions,
                    std::vector<ChunkResult>& results) {
  const size_t n = results.size();
  std::vector<int> large_polygon_vertices;  // of polygons of five or more corners
  for (size_t k = 0; k < n; ++k) {
    for (const tinyobj::shape_t& s : results[k].shapes) {
      if (scans[k].polygon_vertices_before.empty()) continue;
      size_t at = 0;
      for (const unsigned char corners : s.mesh.num_face_vertices) {
        if (corners > 4)
          for (size_t c = 0; c < corners; ++c) large_polygon_vertices.push_back(s.mesh.indices[at + c].vertex_index);
        at += corners;
      }
    }
    if (!polygons_name_earlier_vertices(results[k], scans[k], first_vertex[k])) return false;
  }

  // Polygons split as LoadObj splits them.
  std::sort(large_polygon_vertices.begin(), large_polygon_vertices.end());
  large_polygon_vertices.erase(std::unique(large_polygon_vertices.begin(), large_polygon_vertices.end()),
                               large_polygon_vertices.end());
  const std::vector<std::string_view> large_polygon_lines =
      vertex_line_texts(text, starts, first_vertex, large_polygon_vertices);
  const VertexLineText vertex_line = [&](int v) {
    auto it = std::lower_bound(large_polygon_vertices.begin(), large_polygon_vertices.end(), v);
    return large_polygon_lines[size_t(it - large_polygon_vertices.begin())];
  };
  std::vector<uint8_t> split_ok(n, 1);
  tbb::parallel_for(size_t(0), n, [&](size_t k) {
    if (scans[k].polygon_vertices_before.empty()) return;
    for (tinyobj::shape_t& s : results[k].shapes)
      if (!split_polygons_like_loadobj(&s.mesh, positions, vertex_line)) split_ok[k] = 0;
  });
  return std::find(split_ok.begin(), split_ok.end(), 0) == split_ok.end();
}

// The shapes of every chunk joined into `o`, a `g`/`o` section that runs
// across chunk ends made one shape.
void join_sections(const std::vector<ChunkScan>& scans, std::vector<ChunkResult>& results, ObjParse& o) {
  const size_t n = results.size();
  // The pieces of each section (g/o lines before the piece's chunk, plus its
  // place in the chunk) joined; each shape's arrays allocated once at their
  // full size (growing them piece by piece costs page faults on every copy).
  struct Piece {
    size_t chunk, shape, section;
  };
  std::vector<Piece> pieces;
  for (size_t k = 0, groups_before = 0; k < n; groups_before += scans[k].section_faces.size() - 1, ++k)
    for (size_t j = 0, next = 0; j < scans[k].section_faces.size(); ++j)
      if (scans[k].section_faces[j] != 0) pieces.push_back({k, next++, groups_before + j});
  // A piece's face arrays: in its chunk's shape, or still in its bytes.
  auto shape_bytes = [&](const Piece& p) -> const obj::ShapeBytes* {
    const ChunkResult& r = results[p.chunk];
    return r.shape_bytes.empty() ? nullptr : &r.shape_bytes[p.shape];
  };
  for (size_t first = 0; first < pieces.size();) {
    size_t last = first + 1, faces = 0, corners = 0;
    while (last < pieces.size() && pieces[last].section == pieces[first].section) ++last;
    std::vector<size_t> part_corner, part_face;  // where each piece goes
    for (size_t i = first; i < last; ++i) {
      part_corner.push_back(corners);
      part_face.push_back(faces);
      if (const obj::ShapeBytes* b = shape_bytes(pieces[i])) {
        faces += b->faces;
        corners += b->corners;
      } else {
        const tinyobj::mesh_t& m = results[pieces[i].chunk].shapes[pieces[i].shape].mesh;
        faces += m.num_face_vertices.size();
        corners += m.indices.size();
      }
    }
    o.shapes.push_back(std::move(results[pieces[first].chunk].shapes[pieces[first].shape]));
    if (last > first + 1 || shape_bytes(pieces[first])) {
      // The section's arrays at their full size, every piece copied (or read) in at once.
      tinyobj::mesh_t& to = o.shapes.back().mesh;
      tinyobj::mesh_t head;  // the first piece's arrays
      head.indices.swap(to.indices);
      head.num_face_vertices.swap(to.num_face_vertices);
      head.material_ids.swap(to.material_ids);
      head.smoothing_group_ids.swap(to.smoothing_group_ids);
      // resize's zero fill is serial: the fresh pages' faults are taken in parallel first.
      resize_on_present_pages(to.indices, corners);
      resize_on_present_pages(to.num_face_vertices, faces);
      resize_on_present_pages(to.material_ids, faces);
      resize_on_present_pages(to.smoothing_group_ids, faces);
      tbb::parallel_for(first, last, [&](size_t i) {
        const size_t corner = part_corner[i - first], face = part_face[i - first];
        if (const obj::ShapeBytes* b = shape_bytes(pieces[i])) {
          obj::read_shape_bytes(*b, to.indices.data() + corner, to.num_face_vertices.data() + face,
                                to.material_ids.data() + face, to.smoothing_group_ids.data() + face);
          return;
        }
        copy_faces(i == first ? head : results[pieces[i].chunk].shapes[pieces[i].shape].mesh, to, corner, face);
      });
    }
    first = last;
  }
}

// Where every face falls in one g/o section and is a triangle (nothing to
// split) and there are several chunks: each chunk's faces, which the chunks
// then write straight to their place in the one shape's arrays (no join);
// else empty.
std::vector<size_t> one_section_faces(const std::vector<ChunkScan>& scans) {
  if (scans.size() < 2) return {};
  std::vector<size_t> faces(scans.size(), 0);
  size_t section = 0, groups_before = 0;
  bool any = false;
  for (size_t k = 0; k < scans.size(); groups_before += scans[k].section_faces.size() - 1, ++k) {
    if (!scans[k].polygon_vertices_before.empty()) return {};
    for (size_t j = 0; j < scans[k].section_faces.size(); ++j) {
      if (scans[k].section_faces[j] == 0) continue;
      if (any && groups_before + j != section) return {};
      section = groups_before + j;
      any = true;
      faces[k] = scans[k].section_faces[j];
    }
  }
  return any ? faces : std::vector<size_t>{};
}

// The one section's shape (its arrays sized and the plain chunks' faces in
// already): the other chunks' faces copied in, its name from the chunk of
// its first face; false where a face index is past the `vertex_count`
// vertices (LoadObj warns of that, the reader makes it an error).
bool join_one_section(const std::vector<ChunkScan>& scans, const std::vector<size_t>& faces,
                      const std::vector<size_t>& first_face, std::vector<std::string>& plain_names,
                      std::vector<ChunkResult>& results, size_t vertex_count, ObjParse& o) {
  const size_t n = results.size();
  tinyobj::shape_t& shape = o.shapes[0];
  tinyobj::mesh_t& to = shape.mesh;
  const size_t first =
      size_t(std::find_if(faces.begin(), faces.end(), [](size_t f) { return f != 0; }) - faces.begin());
  shape.name = scans[first].plain ? std::move(plain_names[first]) : results[first].shapes[0].name;
  std::vector<uint8_t> indices_ok(n, 1);
  tbb::parallel_for(size_t(0), n, [&](size_t k) {
    const size_t f = first_face[k];
    // A chunk not plain holds one shape of faces[k] triangles (shapes_match_scan).
    if (!scans[k].plain && faces[k] != 0) copy_faces(results[k].shapes[0].mesh, to, 3 * f, f);
    if (!positions_in_range(std::span(to.indices).subspan(3 * f, 3 * faces[k]), vertex_count)) indices_ok[k] = 0;
  });
  return std::find(indices_ok.begin(), indices_ok.end(), 0) == indices_ok.end();
}

}  // namespace

bool parse_obj_chunked(std::string_view text, const MaterialReaderFactory& readers, size_t chunk_bytes, ObjParse* out,
                       const WorkShare* share) {
  const std::vector<size_t> starts = chunk_starts(text, std::max<size_t>(chunk_bytes, 1));
  const size_t n = starts.size() - 1;
  std::vector<ChunkScan> scans(n);
  if (share && share->shared()) {
    if (!scan_shared(*share, text, starts, &scans)) return false;
  } else {
    tbb::parallel_for(size_t(0), n, [&](size_t k) { scans[k] = obj::scan_chunk(text, starts[k], starts[k + 1]); });
    if (std::any_of(scans.begin(), scans.end(), [](const ChunkScan& s) { return !s.supported; })) return false;
  }
  const std::vector<std::string> prefixes = chunk_prefixes(scans);
  ObjParse& o = *out;
  o = ObjParse{};

  // One section of triangles (not shared): its arrays sized once, the plain
  // chunks' faces parsed straight into them, the others' copied in after.
  const std::vector<size_t> direct_faces = share && share->shared() ? std::vector<size_t>{} : one_section_faces(scans);
  const bool direct = !direct_faces.empty();
  std::vector<size_t> first_face(n + 1, 0);  // direct: each chunk's first face in the shape
  std::vector<std::string> plain_names(n);   // direct: the shape name a plain chunk's faces get
  if (direct) {
    for (size_t k = 0; k < n; ++k) first_face[k + 1] = first_face[k] + direct_faces[k];
    tinyobj::mesh_t& m = o.shapes.emplace_back().mesh;
    resize_on_present_pages(m.indices, 3 * first_face[n]);
    resize_on_present_pages(m.num_face_vertices, first_face[n]);
    resize_on_present_pages(m.material_ids, first_face[n]);
    resize_on_present_pages(m.smoothing_group_ids, first_face[n]);
  }

  // Each chunk with its polygons left whole (split below, once every position is known).
  std::vector<ChunkResult> results(n);
  const std::function<void(size_t)> parse_chunk = [&](size_t k) {
    ChunkResult& r = results[k];
    const std::string_view body = text.substr(starts[k], starts[k + 1] - starts[k]);
    if (scans[k].plain) {
      obj::FaceState state;
      std::string warn;
      if (!face_state(prefixes[k], readers, &state, &warn)) return;  // r.ok stays false: the whole text falls back
      if (direct) {
        tinyobj::mesh_t& m = o.shapes[0].mesh;
        const size_t f = first_face[k];
        obj::parse_plain_chunk_into(body, scans[k], state,
                                    {m.indices.data() + 3 * f, m.num_face_vertices.data() + f,
                                     m.material_ids.data() + f, m.smoothing_group_ids.data() + f, direct_faces[k]},
                                    &r);
        r.ok = r.ok && r.attrib.vertices.size() == 3 * scans[k].vertex_lines;
        plain_names[k] = std::move(state.shape_name);
      } else {
        obj::parse_plain_chunk(body, scans[k], state, &r);
        r.ok = r.ok && shapes_match_scan(r, scans[k]);
      }
      r.warn = std::move(warn);
      return;
    }
    TextStreamBuffer buffer(prefixes[k], body);
    std::istream in(&buffer);
    std::unique_ptr<tinyobj::MaterialReader> reader = readers();
    std::vector<tinyobj::material_t> materials;
    std::string warn, err;
    r.ok = tinyobj::LoadObj(&r.attrib, &r.shapes, &materials, &warn, &err, &in, reader.get(),
                            /*triangulate*/ false, /*default_vcols_fallback*/ false) &&
           keep_warnings(warn, &r.warn) && shapes_match_scan(r, scans[k]);
  };
  // Shared and without polygons (whose splitting changes the arrays), the
  // other parts' chunks are read straight into the joined arrays below.
  const bool in_place = share && share->shared() && std::all_of(scans.begin(), scans.end(), [](const ChunkScan& s) {
                          return s.polygon_vertices_before.empty();
                        });
  std::vector<std::vector<std::byte>> kept;  // the bytes in_place reads from
  if (share && share->shared()) parse_shared(*share, parse_chunk, &results, in_place, &kept);
  else tbb::parallel_for(size_t(0), n, parse_chunk);
  if (std::any_of(results.begin(), results.end(), [](const ChunkResult& r) { return !r.ok; })) return false;

  const std::vector<size_t> first_vertex = join_vertex_arrays(results, scans, o);
  if (direct) return join_one_section(scans, direct_faces, first_face, plain_names, results, first_vertex[n], o);
  // LoadObj warns of a face index past the last vertex (the reader makes that an error).
  const size_t vertex_count = first_vertex[n];
  if (!face_indices_in_range(results, vertex_count)) return false;
  if (!split_polygons(text, starts, scans, first_vertex, o.attrib.vertices, results)) return false;

  join_sections(scans, results, o);
  if (in_place) {
    // The index check above saw only this part's chunks.
    std::vector<uint8_t> ok(o.shapes.size(), 1);
    tbb::parallel_for(size_t(0), o.shapes.size(), [&](size_t i) {
      if (!positions_in_range(o.shapes[i].mesh.indices, vertex_count)) ok[i] = 0;
    });
    if (std::find(ok.begin(), ok.end(), 0) != ok.end()) return false;
  }
  return true;
}

}  // namespace rayform
