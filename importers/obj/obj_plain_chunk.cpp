#include "rayform/importers/obj/obj_plain_chunk.h"

#include "rayform/importers/obj/text_stream_buffer.h"

#include <tiny_obj_loader.h>

#include <istream>
#include <numeric>
#include <string_view>
#include <vector>

namespace rayform::obj {
namespace {

struct Sink {
  tinyobj::attrib_t* attrib;
  tinyobj::mesh_t* mesh;  // the faces go here, or to `target` where it is set
  int material;
  unsigned int smoothing_group;
  const TriangleTarget* target = nullptr;
  size_t faces = 0;              // written to target so far
  bool fits = true;              // every face written to target: a triangle, within its length
  bool positions_from_1 = true;  // false: a corner's position read 0, which LoadObj refuses
};

void vertex(void* s, tinyobj::real_t x, tinyobj::real_t y, tinyobj::real_t z, tinyobj::real_t) {
  std::vector<tinyobj::real_t>& v = static_cast<Sink*>(s)->attrib->vertices;
  v.insert(v.end(), {x, y, z});
}

void normal(void* s, tinyobj::real_t x, tinyobj::real_t y, tinyobj::real_t z) {
  std::vector<tinyobj::real_t>& v = static_cast<Sink*>(s)->attrib->normals;
  v.insert(v.end(), {x, y, z});
}

// LoadObj keeps a `vt` line's first two numbers (the third, w, nowhere).
void texcoord(void* s, tinyobj::real_t x, tinyobj::real_t y, tinyobj::real_t) {
  std::vector<tinyobj::real_t>& v = static_cast<Sink*>(s)->attrib->texcoords;
  v.insert(v.end(), {x, y});
}

// A raw triple as LoadObj's indices (noting a position that read 0).
tinyobj::index_t fixed(Sink& sink, const tinyobj::index_t& raw) {
  sink.positions_from_1 = sink.positions_from_1 && raw.vertex_index > 0;
  return {raw.vertex_index - 1, raw.normal_index - 1, raw.texcoord_index - 1};
}

// A face's raw triples: in a plain chunk (ChunkScan::plain) they hold index
// + 1, 0 for none, which is what LoadObj's fixed indices are plus one, but
// where a position reads 0.
void face(void* s, tinyobj::index_t* corners, int count) {
  Sink& sink = *static_cast<Sink*>(s);
  if (const TriangleTarget* to = sink.target) {
    if (count != 3 || sink.faces == to->faces) {
      sink.fits = false;
      return;
    }
    const size_t f = sink.faces++;
    for (int k = 0; k < 3; ++k) to->corners[3 * f + size_t(k)] = fixed(sink, corners[k]);
    to->face_corners[f] = 3;
    to->materials[f] = sink.material;
    to->smoothing_groups[f] = sink.smoothing_group;
    return;
  }
  tinyobj::mesh_t& m = *sink.mesh;
  for (int k = 0; k < count; ++k) m.indices.push_back(fixed(sink, corners[k]));
  m.num_face_vertices.push_back(static_cast<unsigned char>(count));
  m.material_ids.push_back(sink.material);
  m.smoothing_group_ids.push_back(sink.smoothing_group);
}

// A face in the numbers handed to tinyobjloader, where the scan put none:
// the parse is refused (and the chunked parse falls back).
void unexpected_face(void* s, tinyobj::index_t*, int) { static_cast<Sink*>(s)->fits = false; }

// The face lines of `text` (ChunkScan::faces_read_from on: every corner
// i, i/j, i//k or i/j/k, digits only): each face's raw triples (each index
// + 1, 0 for none, as tinyobjloader's callback reader hands them) to
// `face`. Any other corner (the scan said there is none) clears sink.fits.
void read_faces(std::string_view text, Sink& sink) {
  tinyobj::index_t corners[255];
  for_each_line(text, 0, text.size(), [&](const Line&, std::string_view t) {
    if (t.size() < 2 || t[0] != 'f' || !is_space(t[1])) return true;
    int count = 0;
    for (size_t i = 2;;) {
      while (i < t.size() && is_space(t[i])) ++i;
      if (i == t.size()) break;
      int field[3] = {0, 0, 0};  // position, uv, normal
      int f = 0, digits = 0;
      for (; i < t.size() && !is_space(t[i]); ++i) {
        const char c = t[i];
        if (c >= '0' && c <= '9' && digits < 9) {
          field[f] = 10 * field[f] + (c - '0');
          ++digits;
        } else if (c == '/' && f < 2) {
          ++f;
          digits = 0;
        } else {
          sink.fits = false;
          return false;
        }
      }
      if (count == 255) {
        sink.fits = false;
        return false;
      }
      corners[count++] = {field[0], field[2], field[1]};  // index_t: vertex, normal, texcoord
    }
    face(&sink, corners, count);
    return true;
  });
}

// Both parses: the faces to `to` where it is set, else to a shape in r.
// Where the scan allows it (ChunkScan::faces_read_from), tinyobjloader reads
// only the lines before the first face (every number of the chunk) and the
// face lines after it are read here: their corners are decimals from 1 of
// at most 9 digits, which atoi (tinyobjloader's) reads alike.
void parse(std::string_view body, const ChunkScan& scan, const FaceState& state, const TriangleTarget* to,
           ChunkParse* r) {
  *r = ChunkParse{};
  tinyobj::shape_t shape;
  shape.name = state.shape_name;
  tinyobj::mesh_t& m = shape.mesh;
  if (!to) {
    const size_t faces = std::accumulate(scan.section_faces.begin(), scan.section_faces.end(), size_t(0));
    m.indices.reserve(3 * faces);
    m.num_face_vertices.reserve(faces);
    m.material_ids.reserve(faces);
    m.smoothing_group_ids.reserve(faces);
  }
  r->attrib.vertices.reserve(3 * scan.vertex_lines);
  Sink sink{&r->attrib, &m, state.material, state.smoothing_group, to};
  tinyobj::callback_t callbacks;
  callbacks.vertex_cb = vertex;
  callbacks.normal_cb = normal;
  callbacks.texcoord_cb = texcoord;
  const bool faces_here = scan.faces_read_from <= body.size();
  callbacks.index_cb = faces_here ? unexpected_face : face;
  TextStreamBuffer buffer(faces_here ? body.substr(0, scan.faces_read_from) : body);
  std::istream in(&buffer);
  std::string warn, err;
  r->ok = tinyobj::LoadObjWithCallback(in, callbacks, &sink, nullptr, &warn, &err) && err.empty();
  if (r->ok && faces_here) read_faces(body.substr(scan.faces_read_from), sink);
  r->ok = r->ok && sink.positions_from_1 && sink.fits && (!to || sink.faces == to->faces);
  if (!m.num_face_vertices.empty()) r->shapes.push_back(std::move(shape));
}

}  // namespace

void parse_plain_chunk(std::string_view body, const ChunkScan& scan, const FaceState& state, ChunkParse* r) {
  parse(body, scan, state, nullptr, r);
}

void parse_plain_chunk_into(std::string_view body, const ChunkScan& scan, const FaceState& state,
                            const TriangleTarget& to, ChunkParse* r) {
  parse(body, scan, state, &to, r);
}

}  // namespace rayform::obj
